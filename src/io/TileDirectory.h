#pragma once
// Tile directories (DESIGN sec. 4, 6): `overflight tile` cuts a
// terrain into overlapping (2^k+1)^2 tiles and writes one GeoTIFF per tile
// plus DIR/index.json; renderers load tiles lazily through a TileLoader.
//
// Based on: Zamri, "Data tiling": the terrain is padded to a
// (2^n+1)^2 square, cut into tiles of 2^k+1 samples per side that share their
// edge samples, tiles without source data are flagged 0 and not stored, and
// each tile goes to its own file for fast retrieval.
//
// Layout of DIR:
//   index.json           format "overflight-tiles", version 1, tile_size,
//                        tile_rows/tile_cols, exists (rows of 0/1 flags),
//                        min_height/max_height per tile (world metres, for
//                        culling before loading), source rows/cols and
//                        padded size, h_scale, height mapping (v_scale,
//                        y_offset: metres = v_scale * raw + y_offset), crs
//                        (WKT, may be empty), geotransform (of the terrain
//                        grid's sample 0,0 pixel corner), source checksum
//                        (FNV-1a 64 of the source samples, colors and
//                        mapping), apron (true: every tile has an apron
//                        file), overview (null or its stride and size),
//                        levels (L: reduced levels in each tile file, 0 in
//                        older directories), roughness (per tile the
//                        lod/RottgerQuadtree.h rottger_roughness() of its
//                        samples, [] for tiles flagged 0; null until the
//                        run completes), d2_min_resolution (Röttger's C of
//                        the _d2 files, 0 without them), complete (false
//                        while tiling runs).
//                        Without levels and roughness, tiles are read at full
//                        resolution only.
//   r{R}_c{C}.tif        heights: 1 band UInt16, tile_size^2, DEFLATE,
//                        SetScale(v_scale)/SetOffset(y_offset) so GIS tools
//                        read metres, the source CRS and a geotransform on the
//                        source grid (tile origin = source origin + (C*(s-1),
//                        R*(s-1)) pixels). GeoTIFF overviews m = 1 .. L
//                        hold every 2^m-th sample exactly (not resampled),
//                        ((s-1)/2^m+1)^2: far tiles are read reduced
//                        (lod/TileSet.h "Levels").
//   r{R}_c{C}_rgb.tif    colors: 3 bands Byte (red, green, blue), same grid
//                        and overviews.
//                        A separate file because GeoTIFF bands share one data
//                        type: RGB as UInt16 bands would double its size.
//   r{R}_c{C}_d2.tif     with levels: Float32, ((s-1)/2+1)^2, the full tile's
//                        propagated d2 (lod/RottgerQuadtree.h rottger_d2)
//                        at its even samples, with overviews of every
//                        2^m-th: a tile read at level m takes level m - 1 of
//                        it, so its quadtree has the full tile's d2.
//   r{R}_c{C}_img.tif    with imagery finer than the DEM (index.json
//                        "imagery": its whole texel grid, texel size, level
//                        count, texels per tile; null or absent without):
//                        4 bands Byte (RGBA, alpha = the source's coverage),
//                        the tile's window of the imagery's texel grid
//                        (core/TiledImagery.h: the tile's cells plus a
//                        margin, blended over the elevation colors where
//                        the imagery has no coverage), georeferenced, with
//                        GeoTIFF overviews m = 1 .. levels holding the
//                        box-filtered mip levels (not decimated).
//   r{R}_c{C}_apron.tif  the raw samples just outside the tile (core/TileGrid.h
//                        TileApron): 4 rows of tile_size UInt16 (north, south,
//                        west, east), so that the loader computes normals at
//                        the tile's edges from both sides and seams are not lit
//                        differently; not georeferenced (not a map).
//   overview.tif,        every f-th sample of the terrain (f a power of two,
//   overview_rgb.tif     the smallest that keeps the overview within 2049
//                        samples per side), heights and colors as the tiles,
//                        georeferenced; written only when f > 1. It lets a
//                        renderer place its camera and answer height queries
//                        without loading a terrain larger than memory.
//   .part-K-of-N.json,   the records of part K of a run in N parts
//   .part-K-of-N.overview (io/TileParts.h), from which the last part writes
//                        the overview and index.json.
// Every file is encoded in memory, written to a temporary name (every write
// and the close checked: a full disk fails with "no space left on device")
// and renamed; the heights file is renamed last, so it marks a finished tile.
// A re-run with the same source and tile size keeps a tile only when each of
// its files reads back exactly what it would write (a truncated or foreign
// file is rewritten), so that it ends byte-identical to an uninterrupted
// run; index.json is rewritten with complete = true at the very end, and
// readers refuse an incomplete directory. The tile files are not synced to
// the device one by one (an fsync each cost more than making them): one
// syncfs of the folder precedes the complete index.json or a part's record,
// so a crash before it leaves at worst tiles a re-run finds broken and
// rewrites.
// Readers check index.json against the format's limits and itself
// (io/TileIndex.h) and each file's raster size, bands and type against the
// index before allocating anything from them; a tile whose heights leave
// the range index.json gives it is refused.
#include "core/DataSet.h"
#include "core/TileGrid.h"
#include "io/TileIndex.h"

#include <array>
#include <cstdint>
#include <functional>
#include <string>

namespace overflight {

struct TileWriteOptions {
    int tile_size = 257;
    bool terminal_progress = false; // GDALTermProgress on stderr
    int overview_max_side = 2049;   // see overview_stride()
    // Called after each tile with (tiles done, tiles total); returning false
    // stops the run as an interruption would (throws Error(dir, "interrupted")).
    std::function<bool(int, int)> on_tile;
    // Röttger's roughness and d2 of each tile (lod/TileSet.h
    // rottger_tile_measures(), handed over by the caller: io does not
    // depend on lod). Without them the directory has no reduced levels
    // (levels 0): tiles are read at full resolution only.
    TileMeasures measures;
};

struct TileWriteReport {
    int written = 0, skipped = 0, empty = 0; // empty: flagged 0, not written
    TileIndex index;
};

// FNV-1a 64 of the terrain's size, scales, samples and colors, as 16 hex digits.
std::string terrain_checksum(const Terrain& terrain);

// The decimation of an overview: the smallest power of two f such that
// every f-th sample of a rows x cols grid, ceil((n - 1) / f) + 1 per side,
// fits in max_side (>= 2) samples per side.
int overview_stride(int rows, int cols, int max_side);

// Tiles `data.terrain` into `dir` (created if missing), carrying
// data.info's georeferencing (without it, a local metric frame whose
// projected X is world X and projected Y is -world Z). Throws
// Error("tile size", ...) for a size that is not 2^k+1 >= 3, Error(dir or a
// tile path, ...) for I/O failures.
TileWriteReport write_tile_directory(const DataSet& data, const std::string& dir, const TileWriteOptions& options);

// True when `path` is a directory holding index.json.
bool is_tile_directory(const std::string& path);

// Reads DIR/index.json. Throws Error(DIR/index.json, ...) when missing,
// malformed, inconsistent or incomplete.
TileIndex read_tile_index(const std::string& dir);

// Reads tile (r, c) at `level` (every 2^level-th sample, 0 .. index.levels):
// heights in raw units with the index's mapping, colors, above level 0 the
// full tile's d2 at each sample (when the directory has _d2 files), and at level 0
// with the apron files (index.apron) normals equal to the whole terrain's
// (core/TileGrid.h tile_normals); otherwise normals are left empty (TileSet
// computes one-sided ones: a reduced tile is far away, where the lighting
// seam is a fraction of a pixel). with_normals = false skips the apron.
// Throws Error(tile path, ...) when a file is missing, unreadable, of another
// size, band count or type than the index says, or its heights or d2 values
// are out of range (heights at level 0 must span exactly the index's range).
TileSamples read_tile(const std::string& dir, const TileIndex& index, int r, int c, bool with_normals = true,
                      int level = 0);

// Tile (r, c)'s imagery with its levels. Throws Error(tile path, ...) when
// the directory has none, the file is missing, unreadable or not the size
// the index gives.
TileImagery read_tile_imagery(const std::string& dir, const TileIndex& index, int r, int c);
// A loader of read_tile_imagery for TileSet; empty without imagery tiles.
TileImageryLoader tile_directory_imagery_loader(const std::string& dir, const TileIndex& index);

// A loader for TileSet that reads tiles from `dir`.
TileLoader tile_directory_loader(const std::string& dir, const TileIndex& index);

// The whole source terrain reassembled from the tiles (cropped to the source
// size), for `info` and the non-tiled renderers; info.kind = "tiles",
// info.georeferenced/geotransform/crs_wkt from the index.
DataSet load_tile_directory(const std::string& dir);

// A terrain of at most max_side (>= 2) samples per side standing in for the
// tiled terrain without loading it: every f-th sample (f =
// overview_stride(source rows, cols, max_side)), h_scale multiplied by f, so
// that it covers the same world extent (rounded up to whole overview cells;
// samples beyond the source repeat its edge, as the padded tiles do) and its
// samples are exact source samples. For camera placement, heights under a
// point and `info` when the renderer reads full-resolution tiles lazily
// (TileSet over tile_directory_loader). Reads overview.tif when it was
// written with a stride that divides f, otherwise every f-th sample from
// the tiles one tile at a time; f = 1 is load_tile_directory(). info as
// load_tile_directory, with source_rows/cols of the full terrain and
// metadata "overview_stride". Throws as read_tile_index and read_tile.
DataSet load_tile_directory_overview(const std::string& dir, int max_side = 2049);

// Georeferencing of a GDAL raster (geotransform and CRS WKT), or false when
// it is not a georeferenced raster. Used by `tile` to carry the source's
// georeferencing when the terrain was loaded on the raster's own grid.
bool read_georeferencing(const std::string& path, std::array<double, 6>& geotransform, std::string& crs_wkt,
                         int& rows, int& cols);

// The elevation mapping a GIS tool applies to band 1 of a raster (what
// gdalinfo reports as Offset/Scale and unit): metres = raw * scale + offset.
// Throws Error(path, ...) when GDAL cannot open it.
struct BandMapping {
    double scale = 1.0, offset = 0.0;
    std::string unit;
};
BandMapping read_band_mapping(const std::string& path);

} // namespace overflight
