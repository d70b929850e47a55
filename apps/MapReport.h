#pragma once
// What `info` adds in map terms (DESIGN sec. 6.1): the grid's extent in its
// CRS and in longitude/latitude, the default camera (as a camera file,
// io/CameraFile.h, with its map eye), and with `--at POSITION` the terrain's
// height there (the bilinear surface, DESIGN sec. 3, in the data set's
// vertical units).
#include "CameraOptions.h"
#include "core/DataSet.h"
#include "io/TerrainReport.h"

#include <nlohmann/json.hpp>

#include <string>

namespace overflight::app {

// The figures above as one JSON object: "map_extent" {crs, east_min,
// east_max, north_min, north_max} and "lonlat_extent" {lon_min, lon_max,
// lat_min, lat_max} when `d` is georeferenced (pixel edges, as gdalinfo's
// corners); with the loaded terrain `data` (may be null: a large raster is
// only surveyed) "default_camera" (a camera file's object) and, for a
// non-empty `at` (parsed as parse_position, CRS `crs`), "at" {position, x,
// z, height}. Throws Error("--at", ...) for a bad or outside position.
nlohmann::ordered_json map_report(const TerrainDescription& d, const DataSet* data, const std::string& at,
                                  const std::string& crs);

// The same as "key: value" lines.
std::string map_report_text(const nlohmann::ordered_json& report);

} // namespace overflight::app
