// Based on: DESIGN sec. 4 ("info reports what was done") and sec. 6 (`overflight info [--json]`).
#include "io/TerrainReport.h"

#include "core/ImageryPyramid.h"

#include <nlohmann/json.hpp>

#include <charconv>
#include <cstdlib>
#include <set>
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

// The figures a survey estimates from a sample rather than reads.
const std::set<std::string>& approximate_keys() {
    static const std::set<std::string> keys{"v_scale",       "y_offset",     "elevation_min",
                                            "elevation_max", "nodata_filled", "nodata_share"};
    return keys;
}

nlohmann::ordered_json report(const TerrainDescription& d) {
    const TerrainInfo& info = d.info;
    nlohmann::ordered_json j;
    j["source"] = info.source;
    j["kind"] = info.kind;
    j["driver"] = info.driver;
    j["rows"] = d.rows;
    j["cols"] = d.cols;
    j["source_rows"] = info.source_rows;
    j["source_cols"] = info.source_cols;
    j["h_scale"] = tidy(d.h_scale);
    j["v_scale"] = tidy(d.v_scale);
    j["y_offset"] = tidy(d.y_offset);
    j["vertical_units"] = info.vertical_units;
    j["elevation_min"] = d.elevation_known ? nlohmann::ordered_json(tidy(d.elevation_min)) : nullptr;
    j["elevation_max"] = d.elevation_known ? nlohmann::ordered_json(tidy(d.elevation_max)) : nullptr;
    j["nodata_filled"] = info.nodata_filled;
    j["nodata_share"] = tidy(float(d.nodata_share));
    j["nodata_method"] = info.nodata_method;
    j["crs"] = info.crs;
    j["source_crs"] = info.source_crs;
    j["reprojected"] = info.reprojected;
    j["reprojection"] = info.reprojection;
    j["extent_x"] = tidy(d.extent_x);
    j["extent_z"] = tidy(d.extent_z);
    j["color_source"] = info.color_source;
    const bool imagery = d.imagery_cols > 0;
    j["imagery_size"] = imagery ? nlohmann::ordered_json(std::to_string(d.imagery_cols) + "x" +
                                                         std::to_string(d.imagery_rows))
                                : nullptr;
    j["imagery_resolution"] = imagery ? nlohmann::ordered_json(tidy(float(d.imagery_texel))) : nullptr;
    j["imagery_coverage"] = imagery ? nlohmann::ordered_json(tidy(float(d.imagery_coverage))) : nullptr;
    j["objects"] = d.objects;
    j["lines"] = d.lines;
    if (d.start.given)
        j["vehicle"] = {{"x", d.start.x}, {"z", d.start.z}, {"heading", d.start.heading}};
    else
        j["vehicle"] = nullptr;
    j["approximate"] = !d.approximation.empty();
    j["approximation"] = d.approximation;
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

TerrainDescription describe(const DataSet& data) {
    const Terrain& t = data.terrain;
    TerrainDescription d;
    d.info = data.info;
    d.rows = t.rows();
    d.cols = t.cols();
    d.h_scale = t.h_scale();
    d.v_scale = t.v_scale();
    d.y_offset = t.y_offset();
    d.elevation_min = t.min_height();
    d.elevation_max = t.max_height();
    d.extent_x = t.width();
    d.extent_z = t.depth();
    const double samples = double(t.rows()) * double(t.cols());
    d.nodata_share = samples > 0 ? double(data.info.nodata_filled) / samples : 0.0;
    d.objects = data.scene.objects.size();
    d.lines = data.scene.lines.size();
    d.start = data.start;
    if (const ImageryPyramid* p = t.imagery()) {
        d.imagery_cols = p->level(0).width;
        d.imagery_rows = p->level(0).height;
        d.imagery_texel = p->texel_size(0);
        d.imagery_coverage = p->coverage();
    }
    return d;
}

std::string terrain_report_text(const TerrainDescription& d) {
    const nlohmann::ordered_json j = report(d);
    const bool approximate = !d.approximation.empty();
    std::ostringstream out;
    for (const auto& [key, value] : j.items()) {
        if (key == "metadata" || key == "warnings" || key == "approximate") continue;
        if (value.is_null() && key.rfind("imagery_", 0) == 0) continue; // no imagery finer than the DEM
        const std::string s = plain(value);
        if (s.empty()) continue;
        out << key << ": " << s;
        if (approximate && approximate_keys().count(key) && !value.is_null()) out << " (approximate)";
        out << "\n";
    }
    for (const std::string& w : d.info.warnings) out << "warning: " << w << "\n";
    if (!d.info.metadata.empty()) {
        out << "metadata:\n";
        for (const auto& [key, value] : d.info.metadata) out << "  " << key << " = " << value << "\n";
    }
    return out.str();
}

std::string terrain_report_json(const TerrainDescription& d) {
    // Metadata from arbitrary files may hold invalid UTF-8: replace, never throw.
    return report(d).dump(-1, ' ', false, nlohmann::ordered_json::error_handler_t::replace) + "\n";
}

} // namespace overflight
