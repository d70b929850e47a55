#pragma once
// Objects placed on a terrain (DESIGN sec. 5): houses, vehicles, towers, boxes,
// models and transmission lines, in world X/Z. Plain data: the io layer reads
// them from a `map` or `--scene` file (models included), the gl layer draws them.
#include "core/Image.h"
#include "core/MeshArrays.h"

#include <glm/vec2.hpp>

#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace overflight {

enum class ObjectKind { Box, House, Vehicle, Tower, Model };

const char* to_string(ObjectKind k);

struct SceneObject {
    ObjectKind kind = ObjectKind::Box;
    double x = 0, z = 0;
    std::optional<double> y;   // base height; default: bilinear terrain height at (x, z)
    double width = 10, height = 10, depth = 10; // along X, Y, Z before rotation by heading
    double heading = 0;        // degrees, DESIGN sec. 1 convention
    double scale = 1;          // for models
    Rgb8 color{200, 200, 200};
    std::string model_path;    // for kind Model: OBJ or glTF, resolved against the scene file's folder
    // For kind Model: its triangles in the model's own units and axes, read by
    // the io layer with the scene (load_scene_models), shared between objects.
    std::shared_ptr<const MeshArrays> model;
};

struct TransmissionLine {
    std::vector<glm::dvec2> points; // tower positions, world X/Z
    double height = 40;             // tower height
    double sag = 4;                 // cable sag at mid-span, world units
    Rgb8 color{40, 40, 40};
};

struct Scene {
    std::vector<SceneObject> objects;
    std::vector<TransmissionLine> lines;
    bool empty() const { return objects.empty() && lines.empty(); }
    void append(const Scene& other);
};

} // namespace overflight
