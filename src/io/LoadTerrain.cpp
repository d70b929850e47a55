// Based on: DESIGN sec. 4 (terrain arguments).
#include "io/LoadTerrain.h"

#include "core/DemoIsland.h"
#include "core/Error.h"
#include "io/GdalRaster.h"
#include "io/HovercraftDataSet.h"
#include "io/TileDirectory.h"

#include <filesystem>

namespace overflight {

namespace fs = std::filesystem;

DataSet load_terrain(const std::string& arg, const LoadOptions& options) {
    if (arg.empty()) throw Error("TERRAIN", "empty terrain argument");
    std::error_code ec;
    if (arg == "demo" && !fs::exists(arg, ec)) {
        if (!options.color_path.empty()) throw Error("--color", "the demo island brings its own colors");
        DemoOptions demo;
        demo.size = options.demo_size;
        DataSet data = make_demo_island(demo);
        data.info.source = "demo";
        data.info.kind = "demo";
        return data;
    }
    if (!fs::exists(arg, ec)) {
        // A folder on the way that may not be searched hides the file.
        if (ec == std::errc::permission_denied) throw Error(arg, "permission denied");
        throw Error(arg, "no such file or directory");
    }
    if (fs::is_directory(arg, ec)) {
        if (is_tile_directory(arg)) {
            if (!options.color_path.empty()) throw Error("--color", "a tile directory brings its own colors");
            return load_tile_directory(arg);
        }
        if (fs::is_regular_file(fs::path(arg) / "map", ec)) {
            if (!options.color_path.empty())
                throw Error("--color", "a hovercraft data set brings its own color.ppm");
            return load_hovercraft(arg);
        }
        // Some GDAL formats are directories (ESRI binary grids); anything else
        // is reported as what the user most likely meant: a data set without map.
        try {
            return load_gdal_raster(arg, options.color_path, options.max_direct_size,
                                    std::size_t(options.imagery_memory_mib) << 20);
        } catch (const Error& e) {
            if (e.subject() != arg) throw;
            throw Error(arg, "directory without a `map` file (not a hovercraft data set)");
        }
    }
    return load_gdal_raster(arg, options.color_path, options.max_direct_size,
                            std::size_t(options.imagery_memory_mib) << 20);
}

TerrainDescription describe_terrain(const std::string& arg, const LoadOptions& options, long long exact_samples) {
    std::error_code ec;
    if (arg != "demo" && fs::is_regular_file(arg, ec)) {
        TerrainDescription survey = survey_gdal_raster(arg, options.color_path);
        if ((long long)survey.rows * survey.cols > exact_samples) return survey;
    }
    return describe(load_terrain(arg, options));
}

} // namespace overflight
