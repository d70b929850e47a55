// `overflight tile TERRAIN -o DIR [--tile-size 2^k+1]` (DESIGN sec. 4, 6;
// Zamri, seed 001, "Data tiling"): overlapping tiles, one GeoTIFF per tile,
// DIR/index.json. The format is described in io/TileDirectory.h.
#include "Commands.h"
#include "OptionValues.h"
#include "TerrainOptions.h"
#include "core/Error.h"
#include "io/TileDirectory.h"

#include <cstdio>
#include <memory>

namespace overflight::app {

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
        const TileWriteReport r = write_tile_directory(data, args->out, o);
        std::printf("%s: %dx%d tiles of %d samples, %d written, %d already done, %d without data (flag 0)\n",
                    args->out.c_str(), r.index.grid.tile_rows, r.index.grid.tile_cols, r.index.grid.tile_size, r.written,
                    r.skipped, r.empty);
    });
}

} // namespace overflight::app
