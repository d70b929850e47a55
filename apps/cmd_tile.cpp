// `overflight tile TERRAIN -o DIR [--tile-size 2^k+1]` (DESIGN sec. 4, 6;
// Zamri, "Data tiling"): overlapping tiles, one GeoTIFF per tile,
// DIR/index.json. The format is described in io/TileDirectory.h.
#include "Commands.h"
#include "OptionValues.h"
#include "TerrainOptions.h"
#include "core/Error.h"
#include "io/TileDirectory.h"
#include "lod/TileSet.h"

#include <csignal>
#include <cstdio>
#include <memory>

namespace overflight::app {

namespace {

// Set by SIGINT / SIGTERM: the tiler stops after the tile it is writing, so
// that it exits with one line and removes its temporary file; a re-run
// resumes.
volatile std::sig_atomic_t g_stop = 0;
void request_stop(int) { g_stop = 1; }

} // namespace

void add_tile_command(CLI::App& app) {
    struct Args {
        TerrainArgs terrain;
        std::string out;
        int tile_size = 257;
    };
    auto args = std::make_shared<Args>();
    CLI::App* cmd = app.add_subcommand(
        "tile", "Cut a terrain into overlapping 2^k+1 tiles (16-bit GeoTIFF heights + RGB GeoTIFF colors) and index.json");
    add_terrain_options(*cmd, args->terrain);
    cmd->add_option("-o,--output", args->out, "output folder (created; a re-run resumes an interrupted tiling)")->required();
    cmd->add_option("--tile-size", args->tile_size, "samples per tile side, 2^k+1 (default 257)")
        ->transform(decimal<int>());
    cmd->callback([args, cmd] {
        reject_empty_names(*cmd, {"-o", "--color"});
        const DataSet data = load_terrain(args->terrain);
        TileWriteOptions o;
        o.tile_size = args->tile_size;
        o.terminal_progress = true;
        // Röttger's measures for the reduced levels: io does not depend on lod.
        o.measures = rottger_tile_measures();
        o.on_tile = [](int, int) { return g_stop == 0; };
        std::signal(SIGINT, request_stop);
        std::signal(SIGTERM, request_stop);
        const TileWriteReport r = write_tile_directory(data, args->out, o);
        std::printf("%s: %dx%d tiles of %d samples, %d written, %d already done, %d without data (flag 0)\n",
                    args->out.c_str(), r.index.grid.tile_rows, r.index.grid.tile_cols, r.index.grid.tile_size, r.written,
                    r.skipped, r.empty);
    });
}

} // namespace overflight::app
