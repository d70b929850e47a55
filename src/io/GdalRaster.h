#pragma once
// Any raster GDAL reads as a terrain (DESIGN sec. 4): USGS ASCII DEM,
// GeoTIFF, SRTM .hgt, VTP .bt, ESRI ASCII grid, PNG height maps, ...
//
// Based on: Zamri, sec. 3 (USGS DEM ingestion: Record A header,
// elevation profiles); DESIGN sec. 4 (reprojection, no-data, 16-bit mapping).
#include "core/DataSet.h"
#include "io/TerrainReport.h"

#include <cstddef>
#include <string>

namespace overflight {

// Loads band 1 of `path` as a terrain:
//  - elevations are converted to metres from the band's unit type (ft, US
//    survey foot) after its scale/offset;
//  - a geographic CRS (degrees) is warped to the UTM zone of the raster's centre
//    (same datum), bilinear, with square cells at GDAL's suggested native
//    resolution; a projected raster with non-square or rotated cells is warped
//    within its CRS to square cells of its finer pixel size (at full
//    resolution as the windowed tiler warps each window: io/MetricWarp.h);
//  - no-data samples (the band's no-data value, NaN, and cells outside the source
//    after reprojection) are filled from valid neighbours by GDALFillNodata;
//  - elevations map to 16 bits by choose_height_mapping (HeightMapping.h) over
//    the range of the source's valid elevations, which the reprojected and
//    filled ones lie within; the elevation ramp spans the same range;
//  - hs is the pixel size in metres; a raster without a geotransform has hs = 1;
//  - with `color_path` non-empty, that raster is resampled onto the DEM grid
//    (warped by georeferencing when both have one, else stretched to the grid):
//    RGB bands by color interpretation, else bands 3,2,1 of a 6+ band
//    (Landsat-like) image, else bands 1,2,3, a single band as grey; non-Byte
//    bands are rescaled from their min..max to 0..255. Without it,
//    shade_by_elevation with the sea at 0 m.
// With max_direct_size > 0, a raster whose grid (after any reprojection)
// has more than max_direct_size samples on a side is read decimated by the
// smallest whole factor f that brings it within: each sample the mean of an
// f x f block of source samples (GDAL reads through the raster's overviews
// when it has fine enough ones), then reprojected and filled as above onto
// cells f times coarser; the full raster is never held in memory.
// info.decimation = f and a warning say so.
// info records all of this; a raster of several bands, or with a palette, gets
// a warning (only band 1 is read as heights). Throws Error(path or color_path,
// problem) for a missing, unreadable (permission denied) or garbage file, a
// raster smaller than 2x2 or larger than 65537 samples per side, a USGS DEM
// whose Record A declares more profiles than the file holds, a raster that
// needs more memory than the machine has (all checked before reading any
// sample) or than the process may use, an elevation or extent beyond
// kWorldLimit (core/Terrain.h), or one that is entirely no-data.
// A color raster finer than the DEM is kept at its own resolution
// (io/ImageryRaster.h: load_imagery), read decimated beyond `imagery_bytes`.
DataSet load_gdal_raster(const std::string& path, const std::string& color_path = "", int max_direct_size = 0,
                         std::size_t imagery_bytes = std::size_t(4) << 30);

// What `overflight info` reports of the raster load_gdal_raster would load at
// full resolution, in about a second whatever its size: size, grid after
// reprojection (GDAL's suggested warp output, nothing warped), CRS, extent,
// units and metadata exactly; elevation range, height mapping and no-data
// share from a sample of a few million samples spread over the raster
// (gdal::sample_band), hence `approximation` set. A --color raster is opened,
// not read. Throws the errors of load_gdal_raster that need no full read, and
// "raster is entirely no-data" when every sample was read and none is valid.
TerrainDescription survey_gdal_raster(const std::string& path, const std::string& color_path = "");

} // namespace overflight
