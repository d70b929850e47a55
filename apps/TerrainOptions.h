#pragma once
// The terrain argument shared by every subcommand that takes one (info,
// render, fly, tile, bench, sim; DESIGN sec. 6): the positional TERRAIN
// ("demo", a hovercraft data set directory or a GDAL raster), `--color FILE`
// and `--demo-size N`.
#include "core/DataSet.h"
#include "io/LoadTerrain.h"

#include <CLI/CLI.hpp>

#include <string>

namespace overflight::app {

struct TerrainArgs {
    std::string terrain;     // the positional argument
    LoadOptions load;        // --color, --demo-size, --max-direct-size
    bool warnings_on_stderr = true; // TerrainInfo::warnings as "overflight: SOURCE: warning: ..." lines (not for info)
};

// Adds TERRAIN (required positional), --color FILE and --demo-size N to `cmd`;
// the values land in `args` when the command line is parsed, so `args` must
// outlive the parse (keep it in a static or a shared_ptr owned by the callback).
void add_terrain_options(CLI::App& cmd, TerrainArgs& args);

// The default of --max-direct-size: the largest side a terrain is loaded at
// full resolution by render, bench and fly (8193 = 2^13 + 1 samples, about
// 1 GiB while loading).
inline constexpr int kDefaultMaxDirectSize = 8193;

// Adds --max-direct-size N (default kDefaultMaxDirectSize) for the commands
// that render a terrain loaded whole (render, bench, fly): a GDAL raster with
// more samples per side is read decimated (load_gdal_raster).
void add_max_direct_size_option(CLI::App& cmd, TerrainArgs& args);

// Prints "overflight: SOURCE: warning: WARNING" on stderr.
void print_warning(const std::string& source, const std::string& warning);

// load_terrain(args.terrain, args.load), its warnings printed on stderr;
// throws overflight::Error.
DataSet load_terrain(const TerrainArgs& args);

// As load_terrain, except that a tile directory (`overflight tile`) is opened
// as an overview of at most 2049 samples per side over the same world extent
// (io/TileDirectory.h), for commands whose renderer reads the full-resolution
// tiles lazily (quadtree) or that only describe the terrain (info): a terrain
// larger than memory then stays on disk.
DataSet load_terrain_lazily(const TerrainArgs& args);

// What `info` reports: the tile directory's overview as load_terrain_lazily,
// other terrains through describe_terrain (io/LoadTerrain.h): exact figures
// for a raster of up to about 1025x1025 samples (loaded in about a second),
// a survey (approximate figures, nothing read whole) for larger ones.
TerrainDescription describe_terrain_lazily(const TerrainArgs& args);

} // namespace overflight::app
