#pragma once
// Polygonal models for scene objects of kind `model` (DESIGN sec. 5): Wavefront
// OBJ through tinyobjloader and glTF 2.0 (.gltf, .glb) through tinygltf, read
// into a plain triangle mesh in the model's own units and axes (Y up).
//
// Based on: Szenberg et al. 1997 sec. 5 and 7 (objects described by polygons
// and lines, drawn by OpenGL's Z-buffer over the terrain).
#include "core/MeshArrays.h"
#include "core/Scene.h"

#include <string>

namespace overflight {

// Reads an .obj, .gltf or .glb file (chosen by extension, case-insensitive).
// Faces are triangulated; glTF node transforms are applied; normals missing
// from the file are computed per face. Colors come from the material (OBJ Kd,
// glTF baseColorFactor) and default to `fallback`.
// Throws Error(path, problem) when the file is missing, unreadable, malformed,
// of an unknown type, or holds no triangles.
MeshArrays load_model(const std::string& path, Rgb8 fallback = {200, 200, 200});

// Loads the model of every `model` object of `scene` that has none yet (each
// file and fallback color once). Throws as load_model.
void load_scene_models(Scene& scene);

} // namespace overflight
