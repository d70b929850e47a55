#pragma once
// Private to src/io: the reprojection of a raster onto the square metric grid
// it is loaded or tiled on (DESIGN sec. 4), for any window of that grid, so
// that a sample's value never depends on which window asked for it: the
// loader warps the whole grid, the windowed tiler each tile's window
// (io/GdalRaster.h, io/WindowedTiler.h), and both must agree byte for byte.
//
// GDAL's warper (GDALWarpOperation) does the resampling, bilinear on Float32
// with kNoData outside the source. Two of its choices depend on how a warp is
// cut into chunks, and are fixed here for the whole grid instead:
//   - the transformer. GDAL's exact one (gdalwarp -et 0) costs a PROJ call
//     per sample; its approximate one (-et 0.125) interpolates along each
//     chunk's rows between points it picks, so its result depends on the
//     chunk. Here PROJ is called only on a lattice of every kLatticeStep-th
//     sample of the whole grid (in both directions), and a sample's source
//     position is the bilinear interpolation of the four lattice nodes around
//     it: the same numbers for the same sample in every window, at a PROJ
//     call per kLatticeStep^2 samples;
//   - the resampling scale (GDAL's XSCALE/YSCALE: destination samples per
//     source sample, which widens the bilinear kernel when below 0.95):
//     the whole grid's, as gdalwarp computes it for one chunk covering it.
#include <gdal.h>

#include <array>
#include <string>
#include <vector>

namespace overflight {

// Lattice spacing in grid samples: the interpolated source position is within
// 0.0005 source pixel of PROJ's for UTM from the SRTM DEMs (3" cells) and
// 0.00005 from 1/3" cells (tests/gdal/metric_warp_test.cpp), far below the
// 0.125 pixel gdalwarp accepts by default.
inline constexpr int kLatticeStep = 16;

// The destination grid: geotransform, size and CRS (WKT; empty: the source's).
struct MetricGridSpec {
    std::array<double, 6> gt{0, 1, 0, 0, 0, 1};
    int cols = 0, rows = 0;
    std::string wkt;
};

class MetricWarp {
public:
    // Band 1 of `src` (which must outlive this) onto `grid`; its no-data value,
    // if any, marks missing source samples. Error(subject, ...) when GDAL has
    // no transformation between the CRSs.
    MetricWarp(GDALDatasetH src, const MetricGridSpec& grid, const std::string& subject);
    ~MetricWarp();
    MetricWarp(const MetricWarp&) = delete;
    MetricWarp& operator=(const MetricWarp&) = delete;

    // Rows [row0, row0 + rows) x columns [col0, col0 + cols) of the grid,
    // row by row into `out` (rows * cols floats), kNoData where no source
    // sample reaches. Not thread-safe (PROJ's transformations are not): one
    // MetricWarp per thread. Error(subject, ...) when GDAL fails.
    void read(int row0, int col0, int rows, int cols, float* out) const;

    // The source pixel position of grid position (x, y) (GDAL's pixel/line
    // convention, sample centres at +0.5) by PROJ itself and through the
    // lattice; false where either fails. For measuring the lattice's error.
    bool exact_position(double x, double y, double& sx, double& sy) const;
    bool lattice_position(double x, double y, double& sx, double& sy) const;

private:
    GDALDatasetH src_;
    MetricGridSpec grid_;
    std::string subject_;
    void* exact_ = nullptr; // GDALGenImgProjTransformer from grid pixels to source pixels
    bool has_nodata_ = false;
    double nodata_ = 0;
    double x_scale_ = 1, y_scale_ = 1;
};

} // namespace overflight
