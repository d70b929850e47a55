// What the WebAssembly engine's Node test (engine_node_test.mjs) compares
// against: the demo island as an OFTERR01 file (core/WebTerrainFormat.h, the
// writer `overflight web` uses) and the native `voxel` method's color and
// depth for a fixed camera, as `render --method voxel` casts them (through
// the methods table), before any objects are drawn over them; and the native
// `roam` method's mesh for that camera and a triangle budget, as `render
// --method roam --triangles N` builds it (no vehicle: no focus).
//
//   web_fixture OUT_DIR [DEMO_SIZE] [WIDTHxHEIGHT]
// writes OUT_DIR/terrain.ofterr, native_color.rgb (RGB8, row 0 at the top),
// native_depth.f32 (window depth, little-endian float32, row 0 at the top),
// native_roam_positions.f32 (3 floats per vertex) and native_roam_indices.u32
// (3 per triangle), little-endian, and camera.json (the camera, for
// of_set_camera, and the ROAM budget).
#include "core/DemoIsland.h"
#include "core/Error.h"
#include "core/WebTerrainFormat.h"
#include "methods/MethodTable.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <memory>
#include <string>

using namespace overflight;

namespace {

// Below the page's default budget, so that the test's frames stay quick.
constexpr int kRoamBudget = 20000;

void write_file(const std::string& path, const void* data, std::size_t size) {
    std::ofstream f(path, std::ios::binary);
    f.write(static_cast<const char*>(data), std::streamsize(size));
    if (!f) throw Error(path, "cannot be written");
}

} // namespace

int main(int argc, char** argv) try {
    if (argc < 2) {
        std::cerr << "usage: web_fixture OUT_DIR [DEMO_SIZE] [WIDTHxHEIGHT]\n";
        return 2;
    }
    const std::string dir = argv[1];
    const int size = argc > 2 ? std::atoi(argv[2]) : 513;
    int width = 320, height = 240;
    if (argc > 3 && std::sscanf(argv[3], "%dx%d", &width, &height) != 2) throw Error("size", argv[3]);

    const DataSet d = make_demo_island({.size = size});
    const std::vector<std::uint8_t> file = encode_web_terrain(d.terrain, d.environment, d.start);
    write_file(dir + "/terrain.ofterr", file.data(), file.size());

    // Over the island's south shore, looking north across it and down a little.
    Camera cam;
    cam.eye = {d.terrain.width() * 0.5, d.terrain.max_height() * 0.8 + 50.0, d.terrain.depth() * 0.9};
    cam.heading = 190.0;
    cam.pitch = -8.0;
    cam.fov = 60.0;
    cam.width = width;
    cam.height = height;
    cam.near = 1.0;
    cam.far = std::hypot(d.terrain.width(), d.terrain.depth()) * 1.05;

    const MethodSettings settings;
    const std::unique_ptr<TerrainMethod> voxel = find_terrain_method("voxel")->create({d.terrain, settings, {}});
    MethodStats stats;
    const MethodOutput out = voxel->produce({cam, d.environment, std::nullopt}, stats);
    write_file(dir + "/native_color.rgb", out.color->pixels.data(), out.color->pixels.size() * sizeof(Rgb8));
    write_file(dir + "/native_depth.f32", out.depth->pixels.data(), out.depth->pixels.size() * sizeof(float));

    MethodSettings roam_settings;
    roam_settings.triangles = kRoamBudget;
    const std::unique_ptr<TerrainMethod> roam = find_terrain_method("roam")->create({d.terrain, roam_settings, {}});
    const MethodOutput mesh = roam->produce({cam, d.environment, std::nullopt}, stats);
    write_file(dir + "/native_roam_positions.f32", mesh.mesh->positions.data(),
               mesh.mesh->positions.size() * sizeof(glm::vec3));
    write_file(dir + "/native_roam_indices.u32", mesh.mesh->indices.data(),
               mesh.mesh->indices.size() * sizeof(std::uint32_t));

    std::ofstream json(dir + "/camera.json");
    json.precision(17);
    json << "{\"eye\": [" << cam.eye.x << ", " << cam.eye.y << ", " << cam.eye.z << "], \"heading\": " << cam.heading
         << ", \"pitch\": " << cam.pitch << ", \"fov\": " << cam.fov << ", \"near\": " << cam.near
         << ", \"far\": " << cam.far << ", \"width\": " << cam.width << ", \"height\": " << cam.height
         << ", \"demo_size\": " << size << ", \"roam_budget\": " << kRoamBudget << "}\n";
    if (!json) throw Error(dir + "/camera.json", "cannot be written");
    return 0;
} catch (const std::exception& e) {
    std::cerr << "web_fixture: " << e.what() << "\n";
    return 1;
}
