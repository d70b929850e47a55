#pragma once
// What `overflight info` prints about a terrain (DESIGN sec. 4, 6): size,
// scales and vertical mapping, elevation range in metres, no-data filling,
// CRS and reprojection, extent, color source and GDAL metadata; exact for a
// loaded terrain, approximate (and saying so) for a raster surveyed from its
// metadata and a sample without being read whole (GdalRaster.h).
#include "core/DataSet.h"

#include <cstddef>
#include <string>

namespace overflight {

struct TerrainDescription {
    TerrainInfo info;
    int rows = 0, cols = 0;       // of the terrain grid (after any reprojection)
    float h_scale = 1.0f, v_scale = 1.0f, y_offset = 0.0f;
    bool elevation_known = true;  // false: a survey found no valid sample
    float elevation_min = 0.0f, elevation_max = 0.0f; // metres
    float extent_x = 0.0f, extent_z = 0.0f;
    double nodata_share = 0.0;    // nodata_filled / (rows * cols)
    std::size_t objects = 0, lines = 0;
    // Imagery finer than the samples (core/ImageryPyramid.h): level 0's
    // texels, world units (metres) per texel and the share of the terrain the
    // source covers (mean coverage alpha); 0 when there is none.
    int imagery_cols = 0, imagery_rows = 0;
    double imagery_texel = 0.0, imagery_coverage = 0.0;
    VehicleStart start;
    // Empty when every figure is exact; otherwise how the approximate ones
    // (elevation range, height mapping, no-data share and count) were found.
    std::string approximation;
};

// The exact figures of a loaded terrain.
TerrainDescription describe(const DataSet& data);

// Human-readable report, one "key: value" line per item, metadata indented;
// approximate figures end in " (approximate)".
std::string terrain_report_text(const TerrainDescription& d);

// The same content as one JSON object (one line) with the keys rows, cols,
// h_scale, v_scale, y_offset, elevation_min, elevation_max (null when not
// known), nodata_filled, nodata_share, nodata_method, crs, source_crs,
// reprojected, reprojection, extent_x, extent_z, color_source, imagery_size
// ("COLSxROWS"), imagery_resolution (m per texel), imagery_coverage (share of
// the terrain; the three null without imagery finer than the DEM), metadata
// (object), source, kind, driver, vertical_units, source_rows, source_cols,
// objects, lines, vehicle (object or null), approximate (bool), approximation
// (string, empty when exact), warnings (array of strings; "warning: ..." lines
// in the text report).
std::string terrain_report_json(const TerrainDescription& d);

} // namespace overflight
