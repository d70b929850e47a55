// `overflight info TERRAIN [--json] [--at POSITION [--crs CRS]]` (DESIGN sec.
// 6, 6.1): what a terrain argument resolves to and how it was obtained, and in
// map terms (MapReport.h).
#include "Commands.h"
#include "MapReport.h"
#include "TerrainOptions.h"
#include "io/TerrainReport.h"

#include <cstdio>
#include <memory>
#include <optional>

namespace overflight::app {

void add_info_command(CLI::App& app) {
    struct Args {
        TerrainArgs terrain;
        bool json = false;
        std::string at, crs;
    };
    auto args = std::make_shared<Args>();
    args->terrain.warnings_on_stderr = false; // part of the report instead
    CLI::App* cmd = app.add_subcommand("info", "Describe a terrain: size, scales, elevation range, CRS, no-data, color");
    add_terrain_options(*cmd, args->terrain);
    cmd->add_flag("--json", args->json, "print one JSON object");
    cmd->add_option("--at", args->at, "also print the terrain height at a position (X,Z, lonlat:LON,LAT, crs:E,N)");
    cmd->add_option("--crs", args->crs, "--at's plain pair is E,N in this CRS (EPSG:n, ...)");
    cmd->callback([args] {
        const TerrainDescription d = describe_terrain_lazily(args->terrain);
        // The default camera and --at need the terrain's heights, loaded as
        // render loads it; a raster only surveyed (too large to read whole
        // quickly) is loaded only for --at.
        std::optional<DataSet> data;
        if (d.approximation.empty() || !args->at.empty()) {
            TerrainArgs load = args->terrain;
            load.load.max_direct_size = kDefaultMaxDirectSize;
            data = load_terrain_lazily(load);
        }
        const nlohmann::ordered_json map = map_report(d, data ? &*data : nullptr, args->at, args->crs);
        std::string report;
        if (args->json) {
            nlohmann::ordered_json j = nlohmann::ordered_json::parse(terrain_report_json(d));
            for (const auto& [key, value] : map.items()) j[key] = value;
            report = j.dump(-1, ' ', false, nlohmann::ordered_json::error_handler_t::replace) + "\n";
        } else {
            report = terrain_report_text(d) + map_report_text(map);
        }
        std::fwrite(report.data(), 1, report.size(), stdout);
    });
}

} // namespace overflight::app
