// Based on: DESIGN sec. 4 ("info reports what was done") and sec. 6 (`overflight info [--json]`).
#include "io/TerrainReport.h"

#include <nlohmann/json.hpp>

#include <charconv>
#include <cstdlib>
#include <sstream>

namespace overflight {

namespace {

// The shortest decimal that reads back as the same float (0.05f prints as
// 0.05, not 0.05000000074505806).
double tidy(float f) {
    char buf[32];
    const auto r = std::to_chars(buf, buf + sizeof buf - 1, f);
    *r.ptr = '\0';
    return std::strtod(buf, nullptr);
}

nlohmann::ordered_json report(const DataSet& data) {
    const Terrain& t = data.terrain;
    const TerrainInfo& info = data.info;
    nlohmann::ordered_json j;
    j["source"] = info.source;
    j["kind"] = info.kind;
    j["driver"] = info.driver;
    j["rows"] = t.rows();
    j["cols"] = t.cols();
    j["source_rows"] = info.source_rows;
    j["source_cols"] = info.source_cols;
    j["h_scale"] = tidy(t.h_scale());
    j["v_scale"] = tidy(t.v_scale());
    j["y_offset"] = tidy(t.y_offset());
    j["vertical_units"] = info.vertical_units;
    j["elevation_min"] = tidy(t.min_height());
    j["elevation_max"] = tidy(t.max_height());
    j["nodata_filled"] = info.nodata_filled;
    j["nodata_method"] = info.nodata_method;
    j["crs"] = info.crs;
    j["source_crs"] = info.source_crs;
    j["reprojected"] = info.reprojected;
    j["reprojection"] = info.reprojection;
    j["extent_x"] = tidy(t.width());
    j["extent_z"] = tidy(t.depth());
    j["color_source"] = info.color_source;
    j["objects"] = data.scene.objects.size();
    j["lines"] = data.scene.lines.size();
    if (data.start.given)
        j["vehicle"] = {{"x", data.start.x}, {"z", data.start.z}, {"heading", data.start.heading}};
    else
        j["vehicle"] = nullptr;
    j["warnings"] = info.warnings;
    nlohmann::ordered_json md = nlohmann::ordered_json::object();
    for (const auto& [key, value] : info.metadata) md[key] = value;
    j["metadata"] = md;
    return j;
}

std::string plain(const nlohmann::ordered_json& v) {
    if (v.is_string()) return v.get<std::string>();
    if (v.is_null()) return "-";
    return v.dump();
}

} // namespace

std::string terrain_report_text(const DataSet& data) {
    const nlohmann::ordered_json j = report(data);
    std::ostringstream out;
    for (const auto& [key, value] : j.items()) {
        if (key == "metadata" || key == "warnings") continue;
        const std::string s = plain(value);
        if (s.empty()) continue;
        out << key << ": " << s << "\n";
    }
    for (const std::string& w : data.info.warnings) out << "warning: " << w << "\n";
    if (!data.info.metadata.empty()) {
        out << "metadata:\n";
        for (const auto& [key, value] : data.info.metadata) out << "  " << key << " = " << value << "\n";
    }
    return out.str();
}

std::string terrain_report_json(const DataSet& data) {
    // Metadata from arbitrary files may hold invalid UTF-8: replace, never throw.
    return report(data).dump(-1, ' ', false, nlohmann::ordered_json::error_handler_t::replace) + "\n";
}

} // namespace overflight
