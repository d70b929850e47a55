#include "TerrainOptions.h"

#include "Loading.h"
#include "OptionValues.h"
#include "core/Error.h"
#include "io/TileDirectory.h"

#include <cstdio>

namespace overflight::app {

void add_terrain_options(CLI::App& cmd, TerrainArgs& args) {
    cmd.add_option("terrain", args.terrain,
                   "demo | hovercraft data set directory (map, hf.pgm, color.ppm) | tile directory | any raster GDAL reads")
        ->required();
    cmd.add_option("--color", args.load.color_path,
                   "color raster for a GDAL DEM (orthophoto, Landsat bands 3,2,1, ...): kept at its own resolution "
                   "when finer than the DEM, else resampled onto the DEM grid");
    cmd.add_option("--imagery-memory-mib", args.load.imagery_memory_mib,
                   "imagery finer than the DEM (with its mip levels) beyond this many MiB is shown decimated, with a warning; "
                   "`overflight tile DEM --color IMAGERY -o DIR` keeps it whole in tiles (1..1048576)")
        ->transform(decimal<int>())
        ->capture_default_str();
    cmd.add_option("--demo-size", args.load.demo_size, "samples per side of the demo island (2^n+1, 33..16385)")
        ->transform(decimal<int>())
        ->capture_default_str();
}

void add_max_direct_size_option(CLI::App& cmd, TerrainArgs& args) {
    args.load.max_direct_size = kDefaultMaxDirectSize;
    cmd.add_option("--max-direct-size", args.load.max_direct_size,
                   "a raster with more samples per side is read decimated (block means, through its overviews) to at "
                   "most this many; `overflight tile` keeps the full resolution (2..65537)")
        ->transform(decimal<int>())
        ->capture_default_str();
}

namespace {

// The grid size up to which `info` loads a raster to report exact figures,
// which takes about a second on the development machine (a reprojected one
// longer); larger ones are surveyed.
constexpr long long kInfoExactSamples = 1025LL * 1025LL;

void check_max_direct_size(const TerrainArgs& args) {
    const int n = args.load.max_direct_size;
    if (n != 0 && (n < 2 || n > 65537))
        throw Error("--max-direct-size", std::to_string(n) + " is not a side in 2..65537 samples");
}

void check_imagery_memory(const TerrainArgs& args) {
    const int mib = args.load.imagery_memory_mib;
    if (mib < 1 || mib > 1048576) throw Error("--imagery-memory-mib", std::to_string(mib) + " is not in 1..1048576");
}

DataSet reported(DataSet data, const TerrainArgs& args) {
    if (args.warnings_on_stderr)
        for (const std::string& w : data.info.warnings) print_warning(data.info.source, w);
    return data;
}

} // namespace

void print_warning(const std::string& source, const std::string& warning) {
    std::fprintf(stderr, "overflight: %s: warning: %s\n", source.c_str(), warning.c_str());
}

DataSet load_terrain(const TerrainArgs& args) {
    check_max_direct_size(args);
    check_imagery_memory(args);
    const LoadingScope loading(args.terrain);
    return reported(overflight::load_terrain(args.terrain, args.load), args);
}

DataSet load_terrain_lazily(const TerrainArgs& args) {
    if (!is_tile_directory(args.terrain)) return load_terrain(args);
    if (!args.load.color_path.empty()) throw Error("--color", "a tile directory brings its own colors");
    const LoadingScope loading(args.terrain);
    return reported(load_tile_directory_overview(args.terrain), args);
}

TerrainDescription describe_terrain_lazily(const TerrainArgs& args) {
    if (is_tile_directory(args.terrain)) return describe(load_terrain_lazily(args));
    check_imagery_memory(args);
    const LoadingScope loading(args.terrain);
    return overflight::describe_terrain(args.terrain, args.load, kInfoExactSamples);
}

} // namespace overflight::app
