#pragma once
// Imagery finer than the DEM cut into tiles beside the height tiles, so that
// a terrain whose imagery exceeds memory streams it with its heights.
//
// The imagery's level-0 texel grid is the one an in-memory ImageryPyramid
// of the whole terrain has (core/ImageryPyramid.h): `width` x `height`
// texels over the world rectangle [x0, x0 + width * texel_x] x [z0, z0 +
// height * texel_z]. Tile (r, c) holds a window of that grid: `cols` x `rows`
// texels starting at global texel (u0, v0) (imagery_tile_origin), covering
// the height tile's cells (its samples' squares, so that neighbours overlap
// by the shared edge samples' cells as the heights share those samples)
// plus 2^levels texels on every side. u0 and v0 are multiples of 2^levels
// and the window's sides too, so level m of a tile (box filter halving,
// box_filter_half) holds exactly the texels of level m of the whole
// pyramid: mip mapping a tile is mip mapping the whole (Williams,
// "Pyramidal Parametrics", SIGGRAPH 1983, sec. 2), and a tile's texels are
// seamless with its neighbours'. Exceptions: a texel of the window beyond
// the grid repeats the grid's nearest edge texel (GL's clamp to edge), and
// the whole pyramid folds the last texel of an odd side into its last box
// while a tile halves evenly; both touch only the terrain's outer edge.
//
// levels: the coarsest tile level is the first whose texels are at least
// a DEM cell; farther, the per-sample colors (the imagery at that level,
// colors_from_imagery) take over, so a tile needs no coarser level.
//
// No GL, no file I/O: io writes and reads tiles, gl uploads them.
#include "core/ImageryPyramid.h"
#include "core/TileGrid.h"

#include <functional>
#include <memory>
#include <utility>
#include <vector>

namespace overflight {

struct ImageryTileLayout {
    double x0 = 0, z0 = 0;             // world position of global texel (0, 0)'s corner
    double extent_x = 1, extent_z = 1; // world size of the whole grid (ImageryPyramid::extent_x, _z)
    int width = 0, height = 0;         // the whole grid's texels (0: no imagery tiles)
    int levels = 0;                  // tile levels beyond level 0
    int cols = 0, rows = 0;          // texels per tile at level 0 (multiples of 2^levels)

    bool present() const { return width > 0; }
    // World units per level-0 texel, as ImageryPyramid::texel_x(0), _z(0).
    double texel_x() const { return extent_x / double(width); }
    double texel_z() const { return extent_z / double(height); }
    // World X of global level-0 texel column u's left edge, Z of row v's top edge.
    double x_of(double u) const { return x0 + u * texel_x(); }
    double z_of(double v) const { return z0 + v * texel_z(); }
    // Bytes of one tile's texels with its levels.
    std::size_t tile_bytes() const;
};

// The layout for a terrain tiled by `grid` whose imagery has the level-0
// grid of `x0, z0, extent_x, extent_z, width, height`. Throws
// std::invalid_argument when the extents are not positive finite numbers,
// the grid is empty or a tile would exceed kMaxImageryTileSide texels.
inline constexpr int kMaxImageryTileSide = 16384;
ImageryTileLayout plan_imagery_tiles(const TileGrid& grid, double x0, double z0, double extent_x, double extent_z,
                                     int width, int height);

// Global level-0 texel (u0, v0) of tile (r, c)'s first texel (may be negative).
std::pair<int, int> imagery_tile_origin(const ImageryTileLayout& layout, const TileGrid& grid, int r, int c);

// One tile's imagery: its levels (level m has cols >> m x rows >> m texels).
struct TileImagery {
    int r = 0, c = 0;
    int u0 = 0, v0 = 0;
    std::vector<Image2D<Rgba8>> levels;
    std::size_t bytes() const;
};

// Reads tile (r, c)'s imagery (a tile directory through io).
using TileImageryLoader = std::function<TileImagery(int tile_row, int tile_col)>;

// The imagery tiles a frame shows: the layout, the tile grid's size and
// tile extent, and the tiles loaded for the frame (for the GL layer's
// texture array; tiles absent from `tiles` show the per-sample colors).
struct TileImageryFrame {
    ImageryTileLayout layout;
    int tile_rows = 0, tile_cols = 0;
    double tile_world_size = 0; // world units between tile origins (stride x h_scale)
    std::vector<std::shared_ptr<const TileImagery>> tiles;
};

// Levels 1 .. `levels` of `level0` by box_filter_half (level0 first).
std::vector<Image2D<Rgba8>> imagery_tile_levels(Image2D<Rgba8> level0, int levels);

// Tile (r, c)'s imagery cut from a whole pyramid (its level 0, which must
// have the layout's width x height), texels beyond it clamped to its edge.
TileImagery cut_tile_imagery(const ImageryPyramid& whole, const ImageryTileLayout& layout, const TileGrid& grid, int r,
                             int c);

// Bilinear at world (x, z) on level l exactly as ImageryPyramid::bilinear on
// the whole pyramid (whose level l is max(1, w / 2) per halving over the
// same rectangle): the tile must hold the four texels (it does for any point
// of the tile's samples' cells, l <= layout.levels).
Rgba8 tile_imagery_bilinear(const TileImagery& tile, const ImageryTileLayout& layout, double x, double z, int l);

// The level colors_from_imagery reads for a DEM of h_scale (clamped to the
// tile's levels).
int tile_sample_color_level(const ImageryTileLayout& layout, double h_scale);

// The whole terrain's colors, for the fallback under the imagery, from a
// window of it: `samples` are rows row0 .. and columns col0 .. of a
// rows x cols terrain.
struct FallbackWindow {
    const Terrain* samples = nullptr;
    int row0 = 0, col0 = 0, rows = 0, cols = 0;
};

// Blends a window of level 0 over the terrain's colors exactly as
// blend_over_terrain_colors does on the whole pyramid: `window` holds global
// texels [u0 - feather, u0 - feather + window.width) x [v0 - feather, ...);
// texels outside the global grid take no part in the alpha means and are
// then set to the nearest grid texel (clamped copy). The fallback window
// must hold every sample the texels' bilinear colors read. Returns the
// tile's cols x rows texels (the window without its feather margin).
Image2D<Rgba8> blend_imagery_window(const Image2D<Rgba8>& window, const ImageryTileLayout& layout, int u0, int v0,
                                    int feather, const FallbackWindow& fallback);

} // namespace overflight
