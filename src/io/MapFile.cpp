// Based on: CMSC 23700 project 2a, sec. 6.1 (map file: scales,
// lighting, vehicle start, objects), sec. 4 (sun light, GL_EXP fog); DESIGN sec. 4, 5.
#include "io/MapFile.h"

#include "core/Error.h"
#include "io/Files.h"
#include "io/ModelLoader.h"
#include "io/SceneToml.h"

#include <cmath>
#include <filesystem>
#include <sstream>

namespace overflight {

namespace {

toml::array vec3_array(glm::vec3 v) { return toml::array{double(v.x), double(v.y), double(v.z)}; }

} // namespace

MapFile parse_map(std::string_view text, const std::string& subject, const std::string& base_dir) {
    using namespace toml_io;
    const toml::table root = parse(text, subject);
    check_keys(root,
               {"h_scale", "v_scale", "y_offset", "sun_dir", "sun_color", "ambient", "fog_density", "fog_color", "sky_zenith",
                "sky_horizon", "sea_level", "vehicle", "object", "line"},
               subject, "");
    MapFile map;
    map.h_scale = required_number(root, "h_scale", subject);
    map.v_scale = required_number(root, "v_scale", subject);
    if (!(map.h_scale > 0)) throw Error(subject, "h_scale must be positive");
    if (!(map.v_scale > 0)) throw Error(subject, "v_scale must be positive");
    map.y_offset = optional_number(root, "y_offset", 0.0, subject);
    Environment& env = map.environment;
    env.sun_dir = optional_vec3(root, "sun_dir", env.sun_dir, subject);
    if (env.sun_dir.x == 0 && env.sun_dir.y == 0 && env.sun_dir.z == 0)
        throw Error(subject, "sun_dir must not be the zero vector");
    env.sun_color = optional_vec3(root, "sun_color", env.sun_color, subject);
    env.ambient = optional_vec3(root, "ambient", env.ambient, subject);
    env.fog_density = optional_float(root, "fog_density", env.fog_density, subject);
    if (env.fog_density < 0) throw Error(subject, "fog_density must not be negative");
    env.fog_color = optional_vec3(root, "fog_color", env.fog_color, subject);
    env.sky_zenith = optional_vec3(root, "sky_zenith", env.sky_zenith, subject);
    env.sky_horizon = optional_vec3(root, "sky_horizon", env.sky_horizon, subject);
    if (root.contains("sea_level")) {
        env.sea_level = optional_float(root, "sea_level", 0.0f, subject);
        if (!std::isfinite(*env.sea_level)) throw Error(subject, "sea_level must be a finite number");
    }
    if (const toml::node* v = root.get("vehicle")) {
        const toml::table* t = v->as_table();
        if (!t) throw Error(subject, "line " + std::to_string(v->source().begin.line) + ": vehicle must be a table [vehicle]");
        check_keys(*t, {"x", "z", "heading"}, subject, " in [vehicle]");
        map.start.given = true;
        map.start.x = required_number(*t, "x", subject);
        map.start.z = required_number(*t, "z", subject);
        map.start.heading = optional_number(*t, "heading", 0.0, subject);
    }
    read_objects(root, subject, base_dir, map.scene);
    return map;
}

MapFile load_map(const std::string& path) {
    const auto bytes = read_file_bytes(path);
    const std::string text(bytes.begin(), bytes.end());
    MapFile map = parse_map(text, path, std::filesystem::path(path).parent_path().string());
    load_scene_models(map.scene);
    return map;
}

std::string format_map(const MapFile& map) {
    const Environment& env = map.environment;
    toml::table root{{"h_scale", map.h_scale},
                     {"v_scale", map.v_scale},
                     {"y_offset", map.y_offset},
                     {"sun_dir", vec3_array(env.sun_dir)},
                     {"sun_color", vec3_array(env.sun_color)},
                     {"ambient", vec3_array(env.ambient)},
                     {"fog_density", double(env.fog_density)},
                     {"fog_color", vec3_array(env.fog_color)},
                     {"sky_zenith", vec3_array(env.sky_zenith)},
                     {"sky_horizon", vec3_array(env.sky_horizon)}};
    if (env.sea_level) root.insert("sea_level", double(*env.sea_level));
    if (map.start.given)
        root.insert("vehicle", toml::table{{"x", map.start.x}, {"z", map.start.z}, {"heading", map.start.heading}});
    toml_io::write_objects(map.scene, root);
    std::ostringstream out;
    out << "# Overflight hovercraft data set map (DESIGN sec. 4)\n" << root << "\n";
    return out.str();
}

} // namespace overflight
