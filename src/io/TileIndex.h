#pragma once
// The index.json of a tile directory (layout in io/TileDirectory.h): what it
// holds, its text and its checks. Parsing is a pure function of the text, so
// that it can be fuzzed (fuzz/fuzz_tile_index.cpp) and every declared size is
// checked against the format's limits (core/TileGrid.h) before anything is
// allocated from it.
#include "core/TileGrid.h"
#include "core/TiledImagery.h"

#include <array>
#include <string>

namespace overflight {

struct TileIndex {
    TileGrid grid; // includes the source size
    int padded_size = 0;
    std::string crs_wkt;
    bool georeferenced = false;
    std::array<double, 6> geotransform{0, 1, 0, 0, 0, -1};
    std::string checksum;
    bool complete = false;
    bool apron = false;       // r{R}_c{C}_apron.tif files exist (older directories: no)
    int levels = 0;           // reduced levels in each tile file (older directories: 0)
    int overview_stride = 0;  // 0: no overview files
    int overview_rows = 0, overview_cols = 0;
    std::string source; // what was tiled (path or "demo")
    // Imagery tiles (r{R}_c{C}_img.tif) at the imagery's own resolution;
    // imagery.present() false in directories without them (older ones too).
    ImageryTileLayout imagery;
};

// File name of tile (r, c)'s imagery, in the index as a pattern.
inline constexpr const char* kImageryTileFormat = "GTiff RGBA8 DEFLATE, levels as box-filtered overviews";

// File names of the overview (see io/TileDirectory.h).
inline constexpr const char* kOverviewHeights = "overview.tif";
inline constexpr const char* kOverviewColors = "overview_rgb.tif";

// The index as index.json text (one line per value, ends with a newline).
std::string tile_index_text(const TileIndex& index);

// Parses index.json text. Throws Error(subject, ...) when it is malformed
// JSON, misses a field, holds a number of the wrong kind or outside its
// range, or describes a grid terrain_tile_grid() would not make (sizes,
// flags, height ranges, roughness, levels, overview; validate_tile_index).
// Completeness is not required here (read_tile_index requires it).
TileIndex parse_tile_index(const std::string& text, const std::string& subject);

// The checks parse_tile_index makes after reading the fields; also run on
// an index before it is written, so that no invalid index is ever written.
void validate_tile_index(const TileIndex& index, const std::string& subject);

} // namespace overflight
