#pragma once
// What `overflight info` prints about a loaded terrain (DESIGN sec. 4, 6):
// size, scales and vertical mapping, elevation range in metres, no-data
// filling, CRS and reprojection, extent, color source and GDAL metadata.
#include "core/DataSet.h"

#include <string>

namespace overflight {

// Human-readable report, one "key: value" line per item, metadata indented.
std::string terrain_report_text(const DataSet& data);

// The same content as one JSON object (one line) with the keys rows, cols,
// h_scale, v_scale, y_offset, elevation_min, elevation_max, nodata_filled,
// nodata_method, crs, source_crs, reprojected, reprojection, extent_x,
// extent_z, color_source, metadata (object), source, kind, driver,
// vertical_units, source_rows, source_cols, objects, lines, vehicle (object or
// null), warnings (array of strings; "warning: ..." lines in the text report).
std::string terrain_report_json(const DataSet& data);

} // namespace overflight
