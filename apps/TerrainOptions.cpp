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
                   "color raster for a GDAL DEM (orthophoto, Landsat bands 3,2,1, ...), resampled onto the DEM grid");
    cmd.add_option("--demo-size", args.load.demo_size, "samples per side of the demo island (2^n+1, 33..16385)")
        ->transform(decimal<int>())
        ->capture_default_str();
}

namespace {

DataSet reported(DataSet data, const TerrainArgs& args) {
    if (args.warnings_on_stderr)
        for (const std::string& w : data.info.warnings)
            std::fprintf(stderr, "overflight: %s: warning: %s\n", data.info.source.c_str(), w.c_str());
    return data;
}

} // namespace

DataSet load_terrain(const TerrainArgs& args) {
    const LoadingScope loading(args.terrain);
    return reported(overflight::load_terrain(args.terrain, args.load), args);
}

DataSet load_terrain_lazily(const TerrainArgs& args) {
    if (!is_tile_directory(args.terrain)) return load_terrain(args);
    if (!args.load.color_path.empty()) throw Error("--color", "a tile directory brings its own colors");
    const LoadingScope loading(args.terrain);
    return reported(load_tile_directory_overview(args.terrain), args);
}

} // namespace overflight::app
