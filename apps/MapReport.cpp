// `info` in map terms. See MapReport.h.
#include "MapReport.h"

#include "core/Error.h"
#include "io/MapFrame.h"

#include <algorithm>
#include <cstdio>
#include <optional>

namespace overflight::app {

namespace {

std::string fixed(double v, int decimals) {
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.*f", decimals, v);
    return buf;
}

} // namespace

nlohmann::ordered_json map_report(const TerrainDescription& d, const DataSet* data, const std::string& at,
                                  const std::string& crs) {
    nlohmann::ordered_json j = nlohmann::ordered_json::object();
    if (d.info.georeferenced && !d.info.crs_wkt.empty()) {
        const MapFrame frame(d.info, d.h_scale, d.info.source);
        const double half = 0.5 * d.h_scale;
        const double xs[2] = {-half, d.extent_x + half}, zs[2] = {-half, d.extent_z + half};
        glm::dvec2 lo(1e300), hi(-1e300), llo(1e300), lhi(-1e300);
        for (double x : xs)
            for (double z : zs) {
                const glm::dvec2 m = frame.map_of_world(x, z), l = frame.lonlat_of_world(x, z);
                lo = glm::min(lo, m);
                hi = glm::max(hi, m);
                llo = glm::min(llo, l);
                lhi = glm::max(lhi, l);
            }
        j["map_extent"] = {{"crs", frame.crs_code().empty() ? d.info.crs : frame.crs_code()},
                           {"east_min", lo.x}, {"east_max", hi.x}, {"north_min", lo.y}, {"north_max", hi.y}};
        j["lonlat_extent"] = {{"lon_min", llo.x}, {"lon_max", lhi.x}, {"lat_min", llo.y}, {"lat_max", lhi.y}};
    }
    if (!data) return j;
    const Terrain& t = data->terrain;
    const Camera cam = default_camera(*data, 1280, 720);
    j["default_camera"] = nlohmann::ordered_json::parse(camera_file_text(cam, camera_map_of(cam, *data)));
    if (!at.empty()) {
        const Position p = parse_position(at, "--at", EngineForm::XZ, crs, *data);
        if (p.y) throw Error("--at", "'" + at + "' gives a height; info --at takes a ground position");
        if (!t.contains(float(p.x), float(p.z)))
            throw Error("--at", "point " + fixed(p.x, 3) + "," + fixed(p.z, 3) + " is outside the terrain (X 0.." +
                                    fixed(t.width(), 3) + ", Z 0.." + fixed(t.depth(), 3) + ")");
        j["at"] = {{"position", at}, {"x", p.x}, {"z", p.z}, {"height", t.height_bilinear(float(p.x), float(p.z))}};
    }
    return j;
}

std::string map_report_text(const nlohmann::ordered_json& r) {
    std::string s;
    if (r.contains("map_extent")) {
        const auto& m = r["map_extent"];
        s += "map_extent: E " + fixed(m["east_min"], 2) + ".." + fixed(m["east_max"], 2) + ", N " +
             fixed(m["north_min"], 2) + ".." + fixed(m["north_max"], 2) + " (" + m["crs"].get<std::string>() + ")\n";
        const auto& l = r["lonlat_extent"];
        s += "lonlat_extent: lon " + fixed(l["lon_min"], 6) + ".." + fixed(l["lon_max"], 6) + ", lat " +
             fixed(l["lat_min"], 6) + ".." + fixed(l["lat_max"], 6) + "\n";
    }
    if (!r.contains("default_camera")) return s;
    const auto& c = r["default_camera"];
    s += "default_camera: eye " + fixed(c["eye"][0], 2) + "," + fixed(c["eye"][1], 2) + "," + fixed(c["eye"][2], 2);
    if (c.contains("map")) {
        const auto& e = c["map"]["eye_lonlat"];
        s += " (lonlat:" + fixed(e[0], 6) + "," + fixed(e[1], 6) + "," + fixed(e[2], 1) + ")";
    }
    s += ", heading " + fixed(c["heading"], 2) + ", pitch " + fixed(c["pitch"], 2) + ", fov " + fixed(c["fov"], 1) + "\n";
    if (r.contains("at")) {
        const auto& a = r["at"];
        s += "height_at: " + fixed(a["height"], 2) + " at " + a["position"].get<std::string>() + " (X,Z " +
             fixed(a["x"], 2) + "," + fixed(a["z"], 2) + ")\n";
    }
    return s;
}

} // namespace overflight::app
