#pragma once
// Private to src/io: a color raster (`--color FILE`) read at its own
// resolution onto a terrain's extent, as the level 0 of an ImageryPyramid
// (core/ImageryPyramid.h), and the choice of its RGB bands that the
// DEM-resolution path (GdalRaster.cpp) shares.
//
// Based on: DESIGN sec. 4 (`--color FILE`, rasters through GDAL).
#include "core/ImageryPyramid.h"
#include "io/Gdal.h"

#include <array>
#include <cstddef>
#include <memory>
#include <string>
#include <vector>

namespace overflight {

// Default bound on the imagery's memory (level 0 and its mips, 4 bytes a texel).
inline constexpr std::size_t kDefaultImageryMemory = std::size_t(4) << 30;

// gdal_translate options picking a color raster's RGB bands: by color
// interpretation, else bands 3,2,1 of a 6+ band (Landsat-like) image, else
// bands 1,2,3, a palette expanded, a single band as grey; non-Byte bands
// stretched from their min..max to 0..255. `bands_used` and `rescaled` say
// which (for TerrainInfo::color_source).
std::vector<std::string> color_band_options(GDALDatasetH src, std::string& bands_used, bool& rescaled);

// The terrain's pixel grid the imagery is registered to: rows x cols DEM
// pixels of h_scale world units whose centres are the terrain's samples, and
// their georeferencing (GDAL geotransform and CRS) when georeferenced.
struct ImageryTarget {
    int rows = 0, cols = 0;
    double h_scale = 1.0;
    bool georeferenced = false;
    std::array<double, 6> gt{0, 1, 0, 0, 0, 1};
    std::string wkt;
};

struct ImageryLoad {
    std::shared_ptr<ImageryPyramid> pyramid; // null: the raster is not finer than the DEM
    std::string description;                 // for TerrainInfo::color_source
    std::string warning;                     // non-empty when decimated to fit the memory bound
};

// Reads `color_path` onto the target's extent at the raster's own resolution:
// with georeferencing on both sides, warped (GDALWarp, bilinear) into the
// target's CRS over the DEM's pixel extent at the pixel size GDAL suggests for
// the raster in that CRS (GDALSuggestedWarpOutput2); without, stretched over
// the DEM's pixel extent at the raster's own size. Texels outside the source
// or on its no-data get alpha 0 (the warp's destination alpha), as do pure
// black texels (rasters without declared no-data fill their outside with 0).
// A raster whose pixel is not finer than the DEM's (or, stretched, not larger
// than the grid) is left to the DEM-resolution path: pyramid null. Imagery of
// more than `memory_bound` bytes is read decimated by the smallest whole
// factor that fits, with a warning that says to tile it for its full
// resolution (`overflight tile` writes imagery tiles that the quadtree
// streams). Throws Error(color_path, ...) for a raster with a geotransform but no CRS over a georeferenced DEM, one whose
// CRS GDAL cannot transform to the DEM's, and one that does not overlap it.
ImageryLoad load_imagery(const std::string& color_path, const ImageryTarget& target,
                         std::size_t memory_bound = kDefaultImageryMemory);

// The texel grid load_imagery warps a georeferenced color raster onto over a
// georeferenced DEM (the same numbers), for reading it in windows: the
// target's map extent xmin .. xmax, ymin .. ymax in width x height texels.
struct ImageryGrid {
    bool finer = false; // false: the raster is not finer than the DEM (load_imagery gives no pyramid)
    std::vector<std::string> band_options; // color_band_options of the raster
    std::string description;               // as ImageryLoad::description, without the texel count
    double xmin = 0, xmax = 0, ymin = 0, ymax = 0;
    int width = 0, height = 0;
};
// Throws as load_imagery; Error(color_path, "...") also when either side
// is not georeferenced (only a georeferenced pair is read in windows).
ImageryGrid plan_imagery_grid(const std::string& color_path, const ImageryTarget& target);

// Texels [u0, u0 + w) x [v0, v0 + h) of the grid (any of them may lie
// outside it) warped from `picked` (the raster translated lazily with the
// grid's band options), bilinear, with the warp's alpha and the exact
// transformer (no approximation: a texel does not depend on the window
// that reads it); pure black texels get alpha 0 as in load_imagery.
Image2D<Rgba8> warp_imagery_window(GDALDatasetH picked, const ImageryGrid& grid, const std::string& target_wkt, int u0,
                                   int v0, int w, int h, const std::string& subject);

// A color image larger than the terrain's grid (a hovercraft data set's
// color.ppm) as imagery over the grid's squares, [0, width] x [0, depth],
// fully covered.
std::shared_ptr<ImageryPyramid> imagery_over_cells(const Image2D<Rgb8>& image, double width, double depth);

} // namespace overflight
