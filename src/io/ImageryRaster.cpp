// See ImageryRaster.h.
#include "io/ImageryRaster.h"

#include "core/Error.h"

#include <cpl_conv.h>
#include <cpl_error.h>
#include <cpl_string.h>
#include <gdal_alg.h>
#include <ogr_srs_api.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace overflight {

namespace {

std::string number(double v) {
    char buf[40];
    std::snprintf(buf, sizeof buf, "%.17g", v);
    return buf;
}

// Reads the warped or stretched RGB (+ alpha) dataset into texels.
Image2D<Rgba8> read_texels(GDALDatasetH ds, bool has_alpha, const std::string& subject) {
    const int w = GDALGetRasterXSize(ds), h = GDALGetRasterYSize(ds), bands = GDALGetRasterCount(ds);
    const int colour_bands = has_alpha ? bands - 1 : bands;
    Image2D<Rgba8> img;
    try {
        img.resize(w, h, Rgba8{0, 0, 0, 255});
    } catch (const std::bad_alloc&) {
        throw Error(subject, "not enough memory for " + std::to_string(w) + "x" + std::to_string(h) + " texels of imagery");
    }
    auto* bytes = reinterpret_cast<GByte*>(img.pixels.data());
    for (int c = 0; c < 4; ++c) {
        if (c == 3 && !has_alpha) break;
        const int band = c == 3 ? bands : std::min(c + 1, colour_bands);
        CPLErrorReset();
        if (GDALRasterIO(GDALGetRasterBand(ds, band), GF_Read, 0, 0, w, h, bytes + c, w, h, GDT_Byte, 4,
                         GSpacing(4) * w) != CE_None)
            throw Error(subject, "unreadable raster: " + gdal::last_error("read failed"));
    }
    for (Rgba8& t : img.pixels)
        if (t.r == 0 && t.g == 0 && t.b == 0) t.a = 0;
    return img;
}

// The smallest whole factor by which w x h texels (and their mips, a third
// more) fit in `bound` bytes.
int decimation_for(double w, double h, std::size_t bound) {
    const double bytes = w * h * 4.0 * 4.0 / 3.0;
    if (bytes <= double(bound)) return 1;
    return int(std::ceil(std::sqrt(bytes / double(bound))));
}

// The grid of a georeferenced raster over a georeferenced DEM: map extent
// and texel counts at the raster's suggested resolution.
struct GeoGrid {
    double res, xmin, xmax, ya, yb, w, h;
};
GeoGrid geo_grid(GDALDatasetH picked, const ImageryTarget& target, const std::string& color_path) {
    GeoGrid g;
    const gdal::SuggestedWarpOutput out(picked, target.wkt, color_path, "cannot place it on the DEM");
    g.res = std::abs(out.geotransform[1]);
    g.xmin = target.gt[0];
    g.xmax = target.gt[0] + target.gt[1] * target.cols;
    g.ya = target.gt[3];
    g.yb = target.gt[3] + target.gt[5] * target.rows;
    // The raster's footprint in the DEM's CRS (the suggested grid's bounds)
    // must meet the DEM's extent; windows cut from a raster elsewhere would
    // hold nothing but the fallback.
    const double cx0 = out.geotransform[0], cx1 = cx0 + out.geotransform[1] * out.cols;
    const double cy0 = out.geotransform[3], cy1 = cy0 + out.geotransform[5] * out.rows;
    if (std::max(std::min(cx0, cx1), g.xmin) >= std::min(std::max(cx0, cx1), g.xmax) ||
        std::max(std::min(cy0, cy1), std::min(g.ya, g.yb)) >= std::min(std::max(cy0, cy1), std::max(g.ya, g.yb)))
        throw Error(color_path, "color raster does not overlap the DEM");
    g.w = std::max(1.0, std::round((g.xmax - g.xmin) / g.res));
    g.h = std::max(1.0, std::round(std::abs(g.yb - g.ya) / g.res));
    return g;
}

} // namespace

std::vector<std::string> color_band_options(GDALDatasetH src, std::string& bands_used, bool& rescaled) {
    const int bands = GDALGetRasterCount(src);
    std::vector<int> pick;
    std::vector<std::string> opts;
    int r = 0, g = 0, b = 0;
    for (int k = 1; k <= bands; ++k) {
        const GDALColorInterp ci = GDALGetRasterColorInterpretation(GDALGetRasterBand(src, k));
        if (ci == GCI_RedBand && !r) r = k;
        if (ci == GCI_GreenBand && !g) g = k;
        if (ci == GCI_BlueBand && !b) b = k;
    }
    const bool palette = bands == 1 && GDALGetRasterColorTable(GDALGetRasterBand(src, 1)) != nullptr;
    if (r && g && b) {
        pick = {r, g, b};
        bands_used = "RGB bands";
    } else if (bands >= 6) {
        pick = {3, 2, 1}; // Landsat TM/ETM+: bands 3, 2, 1 are red, green, blue
        bands_used = "bands 3,2,1";
    } else if (bands >= 3) {
        pick = {1, 2, 3};
        bands_used = "bands 1,2,3";
    } else if (palette) {
        pick = {1};
        opts = {"-expand", "rgb"};
        bands_used = "palette";
    } else {
        pick = {1};
        bands_used = "band 1 as grey";
    }
    for (int k : pick) {
        opts.push_back("-b");
        opts.push_back(std::to_string(k));
    }
    rescaled = false;
    if (GDALGetRasterDataType(GDALGetRasterBand(src, pick[0])) != GDT_Byte) {
        // Each band stretched from its own min..max: a 16-bit orthophoto or a
        // reflectance raster would otherwise be black or clipped.
        opts.insert(opts.end(), {"-ot", "Byte", "-scale"});
        rescaled = true;
    }
    return opts;
}

ImageryLoad load_imagery(const std::string& color_path, const ImageryTarget& target, std::size_t memory_bound) {
    gdal::Dataset src = gdal::open_raster(color_path);
    std::string bands_used;
    bool rescaled = false;
    const std::vector<std::string> opts = color_band_options(src.get(), bands_used, rescaled);
    double cgt[6];
    const bool has_gt = GDALGetGeoTransform(src.get(), cgt) == CE_None;
    const bool has_crs = GDALGetSpatialRef(src.get()) != nullptr;
    const bool dem_geo = target.georeferenced && !target.wkt.empty();
    if (dem_geo && has_gt && !has_crs)
        throw Error(color_path, "has a geotransform but no CRS: cannot place it on the DEM");
    const double extent_x = target.h_scale * target.cols, extent_z = target.h_scale * target.rows;
    const double x0 = -0.5 * target.h_scale, z0 = -0.5 * target.h_scale;
    ImageryLoad out;
    gdal::Dataset picked = gdal::translate_lazily(src.get(), opts, color_path);
    gdal::Dataset texels;
    bool has_alpha = false;
    std::string how;
    int factor = 1;
    if (dem_geo && has_gt) {
        const GeoGrid grid = geo_grid(picked.get(), target, color_path);
        const double dem_px = std::abs(target.gt[1]);
        // Within 1 % of the DEM's pixel: nothing finer to show.
        if (grid.res >= 0.99 * dem_px) return out;
        const double xmin = grid.xmin, xmax = grid.xmax, ya = grid.ya, yb = grid.yb;
        double w = grid.w, h = grid.h;
        factor = decimation_for(w, h, memory_bound);
        w = std::max(1.0, std::round(w / factor));
        h = std::max(1.0, std::round(h / factor));
        texels = gdal::warp(picked.get(),
                            {"-t_srs", target.wkt, "-te", number(xmin), number(std::min(ya, yb)), number(xmax),
                             number(std::max(ya, yb)), "-ts", number(w), number(h), "-r",
                             factor > 1 ? "average" : "bilinear", "-dstalpha"},
                            color_path);
        has_alpha = true;
        char buf[120];
        std::snprintf(buf, sizeof buf, "warped onto the DEM's extent at %.3g m per texel (bilinear)",
                      (xmax - xmin) / w);
        how = buf;
    } else {
        const int cols = GDALGetRasterXSize(src.get()), rows = GDALGetRasterYSize(src.get());
        if (cols <= target.cols && rows <= target.rows) return out;
        factor = decimation_for(cols, rows, memory_bound);
        std::vector<std::string> stretch = opts;
        stretch.insert(stretch.end(), {"-outsize", std::to_string(std::max(1, cols / factor)),
                                       std::to_string(std::max(1, rows / factor)), "-r", "average"});
        texels = gdal::translate(src.get(), stretch, color_path);
        how = "stretched over the DEM's extent at its own " + std::to_string(cols) + "x" + std::to_string(rows) +
              " (no common georeferencing)";
    }
    Image2D<Rgba8> level0 = read_texels(texels.get(), has_alpha, color_path);
    if (std::none_of(level0.pixels.begin(), level0.pixels.end(), [](const Rgba8& t) { return t.a > 0; }))
        throw Error(color_path, "color raster does not overlap the DEM");
    if (factor > 1)
        out.warning = color_path + ": imagery of more than " + std::to_string(memory_bound >> 20) +
                      " MiB (--imagery-memory-mib); shown decimated by " + std::to_string(factor) + " to " +
                      std::to_string(level0.width) + "x" + std::to_string(level0.height) +
                      "; for its full resolution tile it (overflight tile DEM --color " + color_path +
                      " -o DIR) and view DIR, whose quadtree streams the imagery tiles";
    out.description = color_path + " (" + bands_used + (rescaled ? ", rescaled to 8 bits" : "") + ", " + how + ", " +
                      std::to_string(level0.width) + "x" + std::to_string(level0.height) + " texels)";
    out.pyramid = std::make_shared<ImageryPyramid>(std::move(level0), x0, z0, extent_x, extent_z);
    return out;
}

ImageryGrid plan_imagery_grid(const std::string& color_path, const ImageryTarget& target) {
    gdal::Dataset src = gdal::open_raster(color_path);
    ImageryGrid out;
    std::string bands_used;
    bool rescaled = false;
    out.band_options = color_band_options(src.get(), bands_used, rescaled);
    double cgt[6];
    const bool has_gt = GDALGetGeoTransform(src.get(), cgt) == CE_None;
    const bool has_crs = GDALGetSpatialRef(src.get()) != nullptr;
    if (!(target.georeferenced && !target.wkt.empty()))
        throw Error(color_path, "imagery is tiled in windows only over a georeferenced DEM");
    if (has_gt && !has_crs) throw Error(color_path, "has a geotransform but no CRS: cannot place it on the DEM");
    if (!has_gt) throw Error(color_path, "imagery is tiled in windows only when it is georeferenced");
    gdal::Dataset picked = gdal::translate_lazily(src.get(), out.band_options, color_path);
    const GeoGrid g = geo_grid(picked.get(), target, color_path);
    out.finer = g.res < 0.99 * std::abs(target.gt[1]);
    out.xmin = g.xmin;
    out.xmax = g.xmax;
    out.ymin = std::min(g.ya, g.yb);
    out.ymax = std::max(g.ya, g.yb);
    out.width = int(g.w);
    out.height = int(g.h);
    char buf[120];
    std::snprintf(buf, sizeof buf, "warped onto the DEM's extent at %.3g m per texel (bilinear), in tiles",
                  (g.xmax - g.xmin) / g.w);
    out.description = color_path + " (" + bands_used + (rescaled ? ", rescaled to 8 bits" : "") + ", " + buf + ", " +
                      std::to_string(out.width) + "x" + std::to_string(out.height) + " texels)";
    return out;
}

Image2D<Rgba8> warp_imagery_window(GDALDatasetH picked, const ImageryGrid& grid, const std::string& target_wkt, int u0,
                                   int v0, int w, int h, const std::string& subject) {
    const double px = (grid.xmax - grid.xmin) / grid.width, py = (grid.ymax - grid.ymin) / grid.height;
    gdal::Dataset texels =
        gdal::warp(picked,
                   {"-t_srs", target_wkt, "-te", number(grid.xmin + u0 * px), number(grid.ymax - (v0 + h) * py),
                    number(grid.xmin + (u0 + w) * px), number(grid.ymax - v0 * py), "-ts", std::to_string(w),
                    std::to_string(h), "-r", "bilinear", "-dstalpha", "-et", "0"},
                   subject);
    return read_texels(texels.get(), true, subject);
}

std::shared_ptr<ImageryPyramid> imagery_over_cells(const Image2D<Rgb8>& image, double width, double depth) {
    Image2D<Rgba8> level0(image.width, image.height);
    for (std::size_t i = 0; i < image.pixels.size(); ++i) {
        const Rgb8 p = image.pixels[i];
        level0.pixels[i] = Rgba8{p.r, p.g, p.b, 255};
    }
    return std::make_shared<ImageryPyramid>(std::move(level0), 0.0, 0.0, width, depth);
}

} // namespace overflight
