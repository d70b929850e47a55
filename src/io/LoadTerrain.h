#pragma once
// The one entry point that turns a terrain argument of the command line into
// a DataSet (DESIGN sec. 4): "demo", a hovercraft data set directory, or any
// raster GDAL reads.
#include "core/DataSet.h"
#include "io/TerrainReport.h"

#include <string>

namespace overflight {

struct LoadOptions {
    std::string color_path; // `--color FILE`: color raster for a GDAL DEM
    int demo_size = 1025;   // `--demo-size N`: samples per side of `demo` (2^n+1)
    // `--max-direct-size N`: a GDAL raster with more samples on a side is read
    // decimated to at most N (load_gdal_raster); 0: always full resolution.
    int max_direct_size = 0;
    // `--imagery-memory-mib N`: imagery finer than the DEM beyond N MiB (with
    // its mips) is read decimated (load_gdal_raster).
    int imagery_memory_mib = 4096;
};

// "demo" -> make_demo_island(demo_size); a directory holding `map` ->
// load_hovercraft; anything else -> load_gdal_raster(arg, color_path,
// max_direct_size).
// Throws Error(path, problem) for a missing file, a directory without `map`
// that GDAL cannot read either, and every loader's errors; Error("--color", ...)
// when a color raster is given for a terrain that brings its own colors.
DataSet load_terrain(const std::string& arg, const LoadOptions& options = {});

// What `info` reports of a terrain argument: describe(load_terrain(...)),
// exact, except for a raster file whose grid holds more than `exact_samples`
// samples, which is surveyed without being read whole (survey_gdal_raster,
// approximate figures). Throws as load_terrain.
TerrainDescription describe_terrain(const std::string& arg, const LoadOptions& options, long long exact_samples);

} // namespace overflight
