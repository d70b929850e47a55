#pragma once
// `overflight tile` for a raster of any size: the source is never held
// whole. Each tile (with its apron) is made from a GDAL window read, in
// parallel over tiles (oneTBB), so that memory stays within a bound whatever
// the source size; it writes the same directory as write_tile_directory()
// over load_gdal_raster() (io/TileDirectory.h, io/GdalRaster.h).
//
// Based on: Zamri, "Data tiling" (the tiles); DESIGN sec. 4 (metres,
// reprojection of geographic rasters to UTM, no-data filling, the 16-bit
// height mapping), done per window:
//   1. a pass over the source in strips of rows finds the elevation range
//      (the height mapping and the colour ramp need the whole range), the
//      no-data count and a checksum;
//   2. each tile reads the window of its samples and apron plus one sample
//      (the hill shading's 3x3); a window holding no-data is widened by
//      the no-data search distance (256 samples) and filled there by
//      GDALFillNodata as the loader fills the whole raster. A warped
//      raster's windows are copied from a cache of blocks of the grid
//      aligned to the tiles (an eighth of the memory bound), each warped
//      once however many windows overlap it.
//   Where the source reports holding no data (GDALGetDataCoverageStatus: a
//   VRT mosaic's areas without sources, a sparse GeoTIFF's unwritten
//   blocks) neither step reads it: the pass counts it void, and a tile with
//   no data within the search distance of its window is the lowest
//   elevation throughout, which the fill would leave it (the same tiles).
// What equals the in-memory tiler, and what does not:
//   - a source on square cells of a projected CRS (or none) without no-data:
//     every tile, apron, d2, overview file byte-identical;
//   - with no-data within 256 samples of valid data: the same (the fill of a
//     sample depends only on the samples within its search distance);
//     beyond it, samples get the lowest elevation of the source, as the
//     loader gives those of voids reaching the raster's border (the wedges
//     outside a reprojected source); the loader searches the whole raster
//     for a void enclosed by data wider than that, which a window cannot see
//     (every tile must give a shared sample the same value);
//   - a geographic raster, or one with rotated or non-square cells, is
//     warped per window as the loader warps the whole grid (io/MetricWarp.h:
//     PROJ on a lattice fixed over the whole grid, one resampling scale), so
//     a sample's value does not depend on which window reads it; the height
//     mapping and the colour ramp span the source's range, as the loader's
//     do: the same tiles, byte for byte;
//   - index.json's checksum is FNV-1a 64 of the source's elevations in
//     metres (row by row) and the plan, not of the loaded terrain: it is
//     known before any tile is cut, as a run in parts needs it.
#include "io/TileDirectory.h"
#include "io/TileParts.h"

#include <cstdint>
#include <functional>
#include <string>

namespace overflight {

struct WindowedTileOptions {
    TileWriteOptions tile;
    // Peak memory of the run (windows, GDAL's block cache, the per-row
    // statistics; not the index of a grid of millions of tiles).
    std::int64_t memory_bytes = std::int64_t(1) << 30;
    TilePart part; // the share of the tile rows to write (io/TileParts.h)
    // Called, before the source is read, with each warning the loader would
    // give (TerrainInfo::warnings, e.g. only band 1 of several is read).
    std::function<void(const std::string& warning)> warn;
    // A georeferenced color raster finer than the DEM (io/ImageryRaster.h):
    // tiled beside the heights at its own resolution (r{R}_c{C}_img.tif,
    // core/TiledImagery.h), each tile warped from its window of the raster,
    // and the samples' colors are the imagery's as load_terrain gives them.
    // Check it with windowed_imagery_applies first.
    std::string color_path;
};

// Whether `color_path` is imagery this tiler reads in windows over the
// raster at `path`: both georeferenced and the color raster finer than the
// DEM. Otherwise `overflight tile` loads them whole (the DEM-resolution
// colors). Throws as load_imagery for a color raster it cannot place.
bool windowed_imagery_applies(const std::string& path, const std::string& color_path);

// Tiles the raster at `path` into `dir`, part options.part of the run; the
// last part to finish (or the only one) writes the overview and the complete
// index.json. Throws Error(path, ...) for a source the loader refuses (as
// load_gdal_raster, except that no side limit applies but the tile grid's,
// kMaxTiledSide), Error("--memory-mib", ...) when the bound cannot hold one
// tile's window, Error(dir, "interrupted") when options.tile.on_tile
// returned false (it is also called with 0 tiles done while the source is
// surveyed), and the write errors of write_tile_directory. The checks made
// before reading (a USGS DEM's Record A against the file's size, at least
// 2x2 samples) and the warnings are the loader's (io/GdalSource.h).
TileWriteReport tile_raster_in_windows(const std::string& path, const std::string& dir,
                                       const WindowedTileOptions& options);

} // namespace overflight
