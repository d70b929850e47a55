#pragma once
// The one entry point that turns a terrain argument of the command line into
// a DataSet (DESIGN sec. 4): "demo", a hovercraft data set directory, or any
// raster GDAL reads.
#include "core/DataSet.h"

#include <string>

namespace overflight {

struct LoadOptions {
    std::string color_path; // `--color FILE`: color raster for a GDAL DEM
    int demo_size = 1025;   // `--demo-size N`: samples per side of `demo` (2^n+1)
};

// "demo" -> make_demo_island(demo_size); a directory holding `map` ->
// load_hovercraft; anything else -> load_gdal_raster(arg, color_path).
// Throws Error(path, problem) for a missing file, a directory without `map`
// that GDAL cannot read either, and every loader's errors; Error("--color", ...)
// when a color raster is given for a terrain that brings its own colors.
DataSet load_terrain(const std::string& arg, const LoadOptions& options = {});

} // namespace overflight
