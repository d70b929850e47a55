// Based on: DESIGN sec. 5 (scene files); Szenberg et al. 1997 (Szenberg et al. 1997),
// sec. 6: polygonal objects (houses, vehicles, transmission lines) on the terrain.
#include "io/SceneFile.h"

#include "io/Files.h"
#include "io/ModelLoader.h"
#include "io/SceneToml.h"

#include <filesystem>

namespace overflight {

Scene parse_scene(std::string_view text, const std::string& subject, const std::string& base_dir) {
    const toml::table root = toml_io::parse(text, subject);
    toml_io::check_keys(root, {"object", "line"}, subject, " (a scene holds [[object]] and [[line]] tables)");
    Scene scene;
    toml_io::read_objects(root, subject, base_dir, scene);
    return scene;
}

Scene load_scene(const std::string& path) {
    const auto bytes = read_file_bytes(path);
    const std::string text(bytes.begin(), bytes.end());
    Scene scene = parse_scene(text, path, std::filesystem::path(path).parent_path().string());
    load_scene_models(scene);
    return scene;
}

} // namespace overflight
