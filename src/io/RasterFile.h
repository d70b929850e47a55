#pragma once
// Plain GeoTIFF writing and single-band reading through GDAL, for code outside
// src/io that must not include GDAL: tests that build small DEMs (feet, float,
// negative, no-data) or read back a depth TIFF.
#include "core/Image.h"

#include <array>
#include <optional>
#include <string>

namespace overflight {

struct RasterGeoreference {
    std::optional<std::array<double, 6>> geotransform; // GDAL order: x0, dx, rx, y0, ry, dy
    std::string crs;                // anything OSRSetFromUserInput takes ("EPSG:32610", WKT); empty: none
    std::optional<double> nodata;   // band no-data value
    std::string unit;               // band unit type, e.g. "m", "ft", "US survey foot"
    double scale = 1.0, offset = 0.0; // band scale/offset (value = raw * scale + offset)
};

// Single-band Float32 GeoTIFF, row 0 at the top, written atomically
// (temporary name + rename). Throws Error(path, ...).
void write_geotiff(const std::string& path, const Image2D<float>& band, const RasterGeoreference& georef = {});

// Band `band` (1-based) of any raster GDAL reads, as floats. Throws Error(path, ...).
Image2D<float> read_raster_band(const std::string& path, int band = 1);

} // namespace overflight
