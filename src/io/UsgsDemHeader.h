#pragma once
// The Record A header of a USGS ASCII DEM: the "general information" Zamri
// extracts before reading the elevation profiles (Zamri, sec. 3: ground
// coordinates of the corners, minimum and maximum elevation, rows and
// columns). GDAL's USGSDEM driver reads the profiles but exposes few of these
// fields, so `overflight info` reads them here.
//
// Based on: Zamri, sec. 3 (data extraction from Record A); USGS
// National Mapping Program Technical Instructions, Standards for Digital
// Elevation Models, Part 2 (1992), Record A data elements 1-18 (fixed columns).
#include <string>
#include <utility>
#include <vector>

namespace overflight {

// Named Record A fields of the first 1024-byte record of `text` (the start of a
// USGS DEM file), e.g. {"USGS_TITLE", "MOUNT ST. HELENS..."}, {"USGS_ELEVATION_UNITS",
// "metres"}, {"USGS_MIN_ELEVATION", "682"}. Fields that are blank or do not parse are
// left out; text shorter than a record yields what fits. Never throws.
std::vector<std::pair<std::string, std::string>> usgs_record_a(const std::string& text);

// The number of profiles (Record A element 16, "n": columns of the grid) that
// `text` declares, or -1 when the field is blank or malformed. Never throws.
long usgs_profile_count(const std::string& text);

// The fewest bytes a file declaring `profiles` profiles can hold: each profile
// starts with a Record B whose elements 1-5 (row and column, m and n, the
// planimetric origin, the datum and the elevation range) take 144 columns, so
// a Record A claiming more profiles than the file has room for is false and
// is rejected before anything is sized from it.
inline constexpr long long kUsgsRecordBHeaderBytes = 144;
long long usgs_minimum_file_size(long profiles);

} // namespace overflight
