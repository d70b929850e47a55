// `overflight tile TERRAIN -o DIR [--tile-size 2^k+1] [--memory-mib M]
// [--part K/N]` and `overflight tile --merge DIR` (DESIGN sec. 4, 6; Zamri,
// "Data tiling"): overlapping tiles, one GeoTIFF per tile, DIR/index.json.
// The format is described in io/TileDirectory.h. A raster file is read in
// windows (io/WindowedTiler.h), in parts when asked (io/TileParts.h); the
// demo, a hovercraft data set and a raster with --color are tiled from
// memory.
#include "Commands.h"
#include "OptionValues.h"
#include "TerrainOptions.h"
#include "core/Error.h"
#include "io/TileDirectory.h"
#include "io/TileParts.h"
#include "io/WindowedTiler.h"
#include "lod/TileSet.h"

#include <csignal>
#include <filesystem>
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
        std::string out, part, merge;
        int tile_size = 257;
        int memory_mib = 1024;
    };
    auto args = std::make_shared<Args>();
    CLI::App* cmd = app.add_subcommand(
        "tile", "Cut a terrain into overlapping 2^k+1 tiles (16-bit GeoTIFF heights + RGB GeoTIFF colors, and RGBA imagery "
        "tiles at the imagery's own resolution when it is finer than the DEM) and index.json");
    add_terrain_options(*cmd, args->terrain);
    cmd->get_option("terrain")->required(false);
    cmd->add_option("-o,--output", args->out, "output folder (created; a re-run resumes an interrupted tiling)");
    cmd->add_option("--tile-size", args->tile_size, "samples per tile side, 2^k+1 (default 257)")
        ->transform(decimal<int>());
    cmd->add_option("--memory-mib", args->memory_mib,
                    "peak memory of tiling a raster file, which is read in windows whatever its size (default 1024)")
        ->transform(decimal<int>());
    cmd->add_option("--part", args->part,
                    "K/N: write only part K of N of the tile rows, so that N jobs tile one source into one folder; "
                    "the last to finish writes index.json");
    cmd->add_option("--merge", args->merge, "write DIR/index.json from the finished parts of a run with --part");
    cmd->callback([args, cmd] {
        reject_empty_names(*cmd, {"-o", "--color", "--merge"});
        if (!args->merge.empty()) {
            if (!args->terrain.terrain.empty() || !args->out.empty() || !args->part.empty())
                throw Error("--merge", "takes only the tile folder (no TERRAIN, -o or --part)");
            const TileIndex ix = merge_tile_parts(args->merge, 0, true).first;
            std::printf("%s: %dx%d tiles of %d samples, index.json complete\n", args->merge.c_str(), ix.grid.tile_rows,
                        ix.grid.tile_cols, ix.grid.tile_size);
            return;
        }
        if (args->terrain.terrain.empty()) throw Error("tile", "TERRAIN is required (or --merge DIR)");
        if (args->out.empty()) throw Error("tile", "-o DIR is required");
        if (args->memory_mib < 64 || args->memory_mib > (1 << 24))
            throw Error("--memory-mib", std::to_string(args->memory_mib) + " is outside 64 .. 16777216");
        TileWriteOptions o;
        o.tile_size = args->tile_size;
        o.terminal_progress = true;
        // Röttger's measures for the reduced levels: io does not depend on lod.
        o.measures = rottger_tile_measures();
        o.on_tile = [](int, int) { return g_stop == 0; };
        std::signal(SIGINT, request_stop);
        std::signal(SIGTERM, request_stop);
        const std::string& terrain = args->terrain.terrain;
        std::error_code ec;
        const std::string& color = args->terrain.load.color_path;
        const bool raster_file = terrain != "demo" && !std::filesystem::is_directory(terrain, ec);
        // Imagery finer than a georeferenced DEM is tiled at its own
        // resolution in windows too; other colors are resampled onto the
        // DEM's grid in memory.
        const bool windowed = raster_file && (color.empty() || windowed_imagery_applies(terrain, color));
        if (!args->part.empty() && !windowed)
            throw Error("--part", "tiles a raster file in parts; the demo, a data set or --color not finer than a "
                                  "georeferenced DEM are tiled whole");
        TileWriteReport r;
        if (windowed) {
            WindowedTileOptions w;
            w.tile = o;
            w.memory_bytes = std::int64_t(args->memory_mib) << 20;
            if (!args->part.empty()) w.part = parse_tile_part(args->part);
            w.warn = [&](const std::string& warning) { print_warning(terrain, warning); };
            w.color_path = color;
            r = tile_raster_in_windows(terrain, args->out, w);
        } else {
            r = write_tile_directory(load_terrain(args->terrain), args->out, o);
        }
        std::string imagery;
        if (r.index.imagery.present())
            imagery = ", imagery " + std::to_string(r.index.imagery.cols) + "x" + std::to_string(r.index.imagery.rows) +
                      " texels per tile with " + std::to_string(r.index.imagery.levels) + " levels";
        std::printf("%s: %dx%d tiles of %d samples%s, %d written, %d already done, %d without data (flag 0)%s\n",
                    args->out.c_str(), r.index.grid.tile_rows, r.index.grid.tile_cols, r.index.grid.tile_size,
                    imagery.c_str(), r.written, r.skipped, r.empty,
                    r.index.complete ? "" : "; index.json waits for the other parts");
    });
}

} // namespace overflight::app
