#pragma once
// A `--scene FILE`: objects placed on a terrain (DESIGN sec. 5), in TOML:
//
//     [[object]]
//     kind = "box"       # box | house | vehicle | tower | model   (required)
//     x = 4890.0         # world X, Z (required); y optional: terrain height
//     z = 13800.0
//     width = 60.0       # along X, Y, Z before rotation by heading (default 10)
//     height = 120.0
//     depth = 60.0
//     heading = 0.0      # degrees, DESIGN sec. 1
//     color = [200, 40, 40]
//     scale = 1.0        # models only
//     file = "tree.obj"  # models only: OBJ or glTF, relative to the scene file
//
//     [[line]]           # transmission line
//     points = [[1000.0, 2000.0], [1400.0, 2100.0]]
//     height = 40.0
//     sag = 4.0
//     color = [40, 40, 40]
#include "core/Scene.h"

#include <string>
#include <string_view>

namespace overflight {

// Parses scene text; errors are Error(subject, "line N: ...") for a TOML
// syntax error, an unknown kind or key, a missing or wrong-typed key.
Scene parse_scene(std::string_view text, const std::string& subject, const std::string& base_dir = "");

// Reads a scene file; model paths are resolved against the file's folder.
Scene load_scene(const std::string& path);

} // namespace overflight
