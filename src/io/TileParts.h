#pragma once
// Tiling one source into one directory by N independent jobs, under any
// batch scheduler (GNU parallel, a Slurm array, Kubernetes indexed jobs):
// part K of N writes the tiles of its share of the tile rows and a record
// of what the index needs from them, DIR/.part-K-of-N.json (per tile its
// height range and Röttger roughness) and, when the directory has an
// overview, DIR/.part-K-of-N.overview (the overview rows whose samples lie
// in its tiles: heights as little-endian UInt16, then red, green and blue
// planes). Whoever sees all N records (the last part to finish, or
// `overflight tile --merge DIR`) writes the overview and the complete
// index.json from them, without reading the source or any tile. The
// records stay (hidden) so that any part can be run again.
#include "io/TileIndex.h"

#include <string>
#include <utility>
#include <vector>

namespace overflight {

struct TilePart {
    int index = 1, count = 1; // part K of N, 1 <= K <= N
};

// Parses "K/N" (decimal, 1 <= K <= N <= 65536); Error("--part", ...) otherwise.
TilePart parse_tile_part(const std::string& text);

// The tile rows [first, end) of part K of N: as equal as whole rows allow,
// in order, covering 0 .. tile_rows - 1 once over the N parts (a part may
// get no row when N > tile_rows).
std::pair<int, int> part_tile_rows(int tile_rows, TilePart part);

// Overview rows [first, end) whose samples (every f-th source sample,
// clamped to the last) lie in tile rows [first_row, end_row): each overview
// row belongs to the tile row holding its source row (the last tile row
// also holds the grid's last sample).
std::pair<int, int> part_overview_rows(const TileIndex& ix, int first_row, int end_row);

// What one part found, the rows of its tiles in row-major order.
struct PartRecord {
    TilePart part;
    std::string checksum; // the index's source checksum
    int tile_size = 0;
    int first_row = 0, end_row = 0;
    std::vector<float> min_height, max_height;  // per tile of its rows
    std::vector<std::vector<float>> roughness; // per tile, empty without levels or data
    int overview_first = 0, overview_end = 0;   // its overview rows
    std::vector<std::uint16_t> overview_heights; // (end - first) x overview_cols
    std::vector<std::uint8_t> overview_rgb;      // three planes of as many
};

// Writes the record of `record.part` into `dir` (atomically).
void write_part_record(const std::string& dir, const PartRecord& record);

// When `dir` holds the records of all N parts of a run (N = `parts`, or 0:
// whichever N has records for the index's checksum), writes the overview and
// the complete index.json from them and returns the complete index; returns
// false in .second when a record is missing. Throws Error(DIR/index.json or
// a record, ...) when the index is missing or broken, or a record belongs to
// another source or layout; with `required`, also when a record is missing
// (naming the missing parts).
std::pair<TileIndex, bool> merge_tile_parts(const std::string& dir, int parts, bool required);

} // namespace overflight
