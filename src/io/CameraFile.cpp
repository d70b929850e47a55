// Camera files as JSON. See CameraFile.h.
#include "CameraFile.h"

#include "Files.h"
#include "core/Error.h"

#include <nlohmann/json.hpp>

#include <cmath>

namespace overflight {

using json = nlohmann::json;

namespace {

constexpr const char* kFormat = "overflight-camera";

double number(const json& j, const char* key, const std::string& path) {
    const json& v = j.at(key);
    if (!v.is_number() || !std::isfinite(v.get<double>())) throw Error(path, std::string(key) + " is not a number");
    return v.get<double>();
}

glm::dvec3 triple(const json& v, const char* key, const std::string& path) {
    if (!v.is_array() || v.size() != 3) throw Error(path, std::string(key) + " is not an array of three numbers");
    glm::dvec3 p;
    for (int k = 0; k < 3; ++k) {
        if (!v[k].is_number() || !std::isfinite(v[k].get<double>()))
            throw Error(path, std::string(key) + " is not an array of three numbers");
        p[k] = v[k].get<double>();
    }
    return p;
}

json array_of(const glm::dvec3& v) { return json::array({v.x, v.y, v.z}); }

} // namespace

CameraFile read_camera_file(const std::string& path, const Camera& defaults) {
    const std::vector<std::uint8_t> bytes = read_file_bytes(path);
    return parse_camera_file(std::string(bytes.begin(), bytes.end()), path, defaults);
}

CameraFile parse_camera_file(const std::string& text, const std::string& path, const Camera& defaults) {
    json j;
    try {
        j = json::parse(text);
    } catch (const json::exception&) {
        throw Error(path, "not a camera file (not JSON)");
    }
    if (!j.is_object()) throw Error(path, "not a camera file (not a JSON object)");
    if (j.contains("format") && j["format"] != kFormat) throw Error(path, "not a camera file (format is not " + std::string(kFormat) + ")");
    CameraFile f;
    Camera& c = f.camera;
    c = defaults;
    if (j.contains("eye")) {
        c.eye = triple(j["eye"], "eye", path);
        f.has_eye = true;
    }
    for (const char* key : {"heading", "pitch", "fov", "near", "far"}) {
        if (!j.contains(key)) continue;
        const double v = number(j, key, path);
        if (key == std::string("heading")) c.heading = v;
        else if (key == std::string("pitch")) c.pitch = v;
        else if (key == std::string("fov")) c.fov = v;
        else if (key == std::string("near")) c.near = v;
        else c.far = v;
    }
    for (const char* key : {"width", "height"}) {
        if (!j.contains(key)) continue;
        const json& v = j[key];
        if (!v.is_number_integer() || v.get<long long>() < 1 || v.get<long long>() > 16384)
            throw Error(path, std::string(key) + " is not a whole number of pixels in 1..16384");
        (key == std::string("width") ? c.width : c.height) = v.get<int>();
    }
    if (j.contains("projection")) {
        const json& v = j["projection"];
        if (v == "shear") c.projection = Projection::Shear;
        else if (v == "tilt") c.projection = Projection::Tilt;
        else throw Error(path, "projection is not \"shear\" or \"tilt\"");
    }
    if (j.contains("map")) {
        const json& m = j["map"];
        if (!m.is_object()) throw Error(path, "map is not an object");
        if (m.contains("crs_name") && m["crs_name"].is_string()) f.map_crs_name = m["crs_name"];
        if (!f.has_eye && m.contains("eye")) {
            if (m.contains("crs") && !m["crs"].is_string()) throw Error(path, "map.crs is not a string (for example \"EPSG:32610\")");
            f.map_eye = CameraFileMapEye{triple(m["eye"], "map.eye", path), m.value("crs", std::string())};
        } else if (!f.has_eye && m.contains("eye_lonlat")) {
            f.map_eye = CameraFileMapEye{triple(m["eye_lonlat"], "map.eye_lonlat", path), "lonlat"};
        }
    }
    if (!f.has_eye && !f.map_eye) throw Error(path, "no eye (give \"eye\": [X, Y, Z] or map.eye_lonlat)");
    try {
        c.validate();
    } catch (const Error& e) {
        throw Error(path, e.problem());
    }
    return f;
}

std::string camera_file_text(const Camera& c, const std::optional<CameraFileMap>& map) {
    json j = {{"format", kFormat},
              {"version", 1},
              {"eye", array_of(c.eye)},
              {"heading", c.heading},
              {"pitch", c.pitch},
              {"fov", c.fov},
              {"projection", to_string(c.projection)},
              {"near", c.near},
              {"far", c.far},
              {"width", c.width},
              {"height", c.height}};
    if (map) {
        j["map"] = {{"crs", map->crs}, {"crs_name", map->crs_name}, {"eye", array_of(map->eye)},
                    {"eye_lonlat", array_of(map->eye_lonlat)}};
    }
    return j.dump(2) + "\n";
}

void write_camera_file(const std::string& path, const Camera& camera, const std::optional<CameraFileMap>& map) {
    const std::string text = camera_file_text(camera, map);
    write_file_atomically(path, text.data(), text.size());
}

} // namespace overflight
