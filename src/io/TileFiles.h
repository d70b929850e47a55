#pragma once
// Private to src/io: the files of a tile directory (layout in
// io/TileDirectory.h) as the in-memory tiler (io/TileDirectory.h) and the
// windowed one (io/WindowedTiler.h) write them, so that both write the same
// bytes for the same samples.
#include "core/TileGrid.h"
#include "io/TileIndex.h"
#include "io/TileRasters.h"

#include <array>
#include <cstdint>
#include <functional>
#include <string>
#include <utility>
#include <vector>

namespace overflight {

enum class TileFile { Heights, Colors, Apron, D2, Imagery };

// DIR/r{R}_c{C}.tif and its _rgb, _apron, _d2 and _img siblings.
std::string tile_path(const std::string& dir, int r, int c, TileFile f);
std::string index_path(const std::string& dir);

// The georeferencing of tile (r, c): the index's, moved to the tile's first sample.
std::array<double, 6> tile_geotransform(const TileIndex& ix, int r, int c);

// Writes DIR/index.json atomically; checked before writing, so that no run
// leaves an index its readers refuse.
void write_index(const std::string& dir, const TileIndex& ix);

// RGBA texels as four planes, the layout RasterSpec takes.
std::vector<std::uint8_t> rgba_planes(const Image2D<Rgba8>& img);

// The georeferencing of an imagery tile whose first texel is global texel
// (u0, v0): the terrain's (north up), at the imagery's texel size; none
// (identity) for a terrain without georeferencing.
std::array<double, 6> imagery_tile_geotransform(const TileIndex& ix, int u0, int v0);

// Colors as three planes (red, green, blue), the layout RasterSpec takes.
std::vector<std::uint8_t> color_planes(const Terrain& t);

// The files of one tile with their contents, in writing order: colors,
// apron, d2, then heights, whose appearing under its final name marks a
// finished tile. Not movable: the specs point into the buffers.
class TileContent {
public:
    // With `imagery` (index with imagery tiles), its file too.
    TileContent(const std::string& dir, const TileIndex& ix, int r, int c, const TileSamples& t, const TileApron& apron,
                const TileMeasures& measures, const TileImagery* imagery = nullptr);
    TileContent(const TileContent&) = delete;
    TileContent& operator=(const TileContent&) = delete;

    // Writes the files with FileSync::Later: the caller's FolderSync makes
    // them durable before an index or a part record says the tile is done.
    void write() const;
    // Whether every file already holds exactly this content.
    bool on_disk() const;

private:
    std::array<double, 6> gt_;
    std::vector<std::uint8_t> rgb_;
    std::vector<std::uint16_t> sides_;
    std::vector<float> even_d2_;
    std::array<double, 6> imagery_gt_{};
    std::vector<std::vector<std::uint8_t>> imagery_planes_; // per level, RGBA planes
    std::vector<const void*> imagery_levels_;               // levels 1.. of them
    std::vector<std::pair<std::string, RasterSpec>> files_;
};

// Every f-th sample of `t` (clamped to its last row and column, with the
// padding's darkened colors there, as cut_tile does): rows x cols samples.
Terrain decimate(const Terrain& t, int f, int rows, int cols);

// overview.tif and overview_rgb.tif holding `overview` (the terrain's every
// ix.overview_stride-th sample), unless a resumed run finds them holding
// exactly this content.
void write_overview(const std::string& dir, const TileIndex& ix, const Terrain& overview, bool resume);

// Hidden files of a run in parts (io/TileParts.h) start with "." and this.
inline constexpr const char* kPartPrefix = "part-";

// Creates `dir` and removes the temporary files a killed run left behind
// (they cannot have cleaned up after themselves); with `mine`, only those
// for which it returns true (a part of a run in parts leaves the other
// parts' files alone: they may be running).
void prepare_folder(const std::string& dir, const std::function<bool(const std::string& name)>& mine = {});

// Whether `dir` holds a run of the same source, tile size and layout, whose
// finished files may be kept (each is still checked before it is).
bool resumable(const std::string& dir, const TileIndex& ix);

} // namespace overflight
