// `overflight info TERRAIN [--json]` (DESIGN sec. 6): what a terrain argument
// resolves to and how it was obtained.
#include "Commands.h"
#include "TerrainOptions.h"
#include "io/TerrainReport.h"

#include <cstdio>
#include <memory>

namespace overflight::app {

void add_info_command(CLI::App& app) {
    struct Args {
        TerrainArgs terrain;
        bool json = false;
    };
    auto args = std::make_shared<Args>();
    args->terrain.warnings_on_stderr = false; // part of the report instead
    CLI::App* cmd = app.add_subcommand("info", "Describe a terrain: size, scales, elevation range, CRS, no-data, color");
    add_terrain_options(*cmd, args->terrain);
    cmd->add_flag("--json", args->json, "print one JSON object");
    cmd->callback([args] {
        const TerrainDescription d = describe_terrain_lazily(args->terrain);
        const std::string report = args->json ? terrain_report_json(d) : terrain_report_text(d);
        std::fwrite(report.data(), 1, report.size(), stdout);
    });
}

} // namespace overflight::app
