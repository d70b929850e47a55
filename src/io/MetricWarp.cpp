// Based on: GDAL's warp API (GDALWarpOperation, GDALGenImgProjTransform and
// the GDALTransformerFunc contract); DESIGN sec. 4 (reprojection to metric
// cells).
#include "io/MetricWarp.h"

#include "core/Error.h"
#include "io/Gdal.h"
#include "io/GdalSource.h"

#include <cpl_string.h>
#include <gdal_alg.h>
#include <gdalwarper.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>

namespace overflight {

namespace {

// A GDAL transformer from the pixels of a window of the grid (origin col0,
// row0) to source pixels: PROJ (through `exact`) at the lattice nodes around
// the window, bilinear between them. GDAL recognises a transformer by the
// GDALTransformerInfo it starts with.
struct Lattice {
    GDALTransformerInfo info{};
    void* exact = nullptr;
    int col0 = 0, row0 = 0;
    long long a0 = 0, b0 = 0; // grid lattice index of the first node held
    int na = 0, nb = 0;       // nodes held along x and y
    std::vector<double> sx, sy;
    std::vector<int> ok;

    // Source position of grid position (gx, gy); false where a node failed.
    // The same arithmetic on the same nodes for a given grid position,
    // whichever window holds them: every window reads the same values.
    bool at(double gx, double gy, double& x, double& y) const {
        const double u = (gx - 0.5) / kLatticeStep, v = (gy - 0.5) / kLatticeStep;
        const long long a = std::clamp((long long)std::floor(u), a0, a0 + na - 2);
        const long long b = std::clamp((long long)std::floor(v), b0, b0 + nb - 2);
        const double fu = u - double(a), fv = v - double(b);
        const std::size_t k = std::size_t(b - b0) * std::size_t(na) + std::size_t(a - a0);
        const std::size_t k1 = k + std::size_t(na);
        if (!ok[k] || !ok[k + 1] || !ok[k1] || !ok[k1 + 1]) return false;
        x = (1 - fv) * ((1 - fu) * sx[k] + fu * sx[k + 1]) + fv * ((1 - fu) * sx[k1] + fu * sx[k1 + 1]);
        y = (1 - fv) * ((1 - fu) * sy[k] + fu * sy[k + 1]) + fv * ((1 - fu) * sy[k1] + fu * sy[k1 + 1]);
        return true;
    }
};

int lattice_transform(void* arg, int dst_to_src, int n, double* x, double* y, double* z, int* success) {
    const Lattice& l = *static_cast<const Lattice*>(arg);
    if (!dst_to_src) {
        // Source to grid (GDAL's check of the source window from the source
        // side): PROJ itself, into the window's pixels.
        const int r = GDALGenImgProjTransform(l.exact, FALSE, n, x, y, z, success);
        for (int i = 0; i < n; ++i) {
            x[i] -= l.col0;
            y[i] -= l.row0;
        }
        return r;
    }
    for (int i = 0; i < n; ++i) {
        double sx, sy;
        success[i] = l.at(x[i] + l.col0, y[i] + l.row0, sx, sy);
        if (success[i]) {
            x[i] = sx;
            y[i] = sy;
        }
    }
    return TRUE;
}

// The lattice nodes around grid rows [row0, row0 + rows) x columns [col0,
// col0 + cols), one node beyond on each side (GDAL also transforms the
// window's edges to find its source window).
Lattice lattice_around(void* exact, int row0, int col0, int rows, int cols) {
    Lattice l;
    std::memcpy(l.info.abySignature, GDAL_GTI2_SIGNATURE, strlen(GDAL_GTI2_SIGNATURE));
    l.info.pszClassName = "OverflightLatticeTransformer";
    l.info.pfnTransform = lattice_transform;
    l.exact = exact;
    l.col0 = col0;
    l.row0 = row0;
    const auto node = [](double g) { return (long long)std::floor((g - 0.5) / kLatticeStep); };
    l.a0 = node(col0) - 1;
    l.b0 = node(row0) - 1;
    l.na = int(node(double(col0) + cols) + 2 - l.a0 + 1);
    l.nb = int(node(double(row0) + rows) + 2 - l.b0 + 1);
    const std::size_t n = std::size_t(l.na) * std::size_t(l.nb);
    l.sx.resize(n);
    l.sy.resize(n);
    l.ok.assign(n, 0);
    std::vector<double> z(n, 0.0);
    for (int j = 0; j < l.nb; ++j)
        for (int i = 0; i < l.na; ++i) {
            const std::size_t k = std::size_t(j) * std::size_t(l.na) + std::size_t(i);
            l.sx[k] = double(l.a0 + i) * kLatticeStep + 0.5;
            l.sy[k] = double(l.b0 + j) * kLatticeStep + 0.5;
        }
    GDALGenImgProjTransform(exact, TRUE, int(n), l.sx.data(), l.sy.data(), z.data(), l.ok.data());
    return l;
}

std::string number(double v) {
    char buf[40];
    std::snprintf(buf, sizeof buf, "%.17g", v);
    return buf;
}

} // namespace

MetricWarp::MetricWarp(GDALDatasetH src, const MetricGridSpec& grid, const std::string& subject)
    : src_(src), grid_(grid), subject_(subject) {
    char** to = grid.wkt.empty() ? nullptr : CSLSetNameValue(nullptr, "DST_SRS", grid.wkt.c_str());
    CPLErrorReset();
    exact_ = GDALCreateGenImgProjTransformer2(src, nullptr, to);
    CSLDestroy(to);
    if (!exact_) throw Error(subject, "cannot reproject raster: " + gdal::last_error("no transformation to the target CRS"));
    GDALSetGenImgProjTransformerDstGeoTransform(exact_, grid.gt.data());
    int has = 0;
    nodata_ = GDALGetRasterNoDataValue(GDALGetRasterBand(src, 1), &has);
    has_nodata_ = has != 0;
    // gdalwarp's scale for one chunk covering the grid, whose source window
    // is the whole source: destination samples per source sample.
    x_scale_ = double(grid.cols) / double(GDALGetRasterXSize(src));
    y_scale_ = double(grid.rows) / double(GDALGetRasterYSize(src));
}

MetricWarp::~MetricWarp() { GDALDestroyGenImgProjTransformer(exact_); }

void MetricWarp::read(int row0, int col0, int rows, int cols, float* out) const {
    std::fill(out, out + std::size_t(rows) * std::size_t(cols), kNoData);
    Lattice lattice = lattice_around(exact_, row0, col0, rows, cols);
    GDALWarpOptions* wo = GDALCreateWarpOptions();
    wo->hSrcDS = src_;
    wo->nBandCount = 1;
    wo->panSrcBands = static_cast<int*>(CPLMalloc(sizeof(int)));
    wo->panSrcBands[0] = 1;
    wo->panDstBands = static_cast<int*>(CPLMalloc(sizeof(int)));
    wo->panDstBands[0] = 1;
    wo->eResampleAlg = GRA_Bilinear;
    wo->eWorkingDataType = GDT_Float32;
    if (has_nodata_) {
        wo->padfSrcNoDataReal = static_cast<double*>(CPLMalloc(sizeof(double)));
        wo->padfSrcNoDataReal[0] = nodata_;
    }
    wo->padfDstNoDataReal = static_cast<double*>(CPLMalloc(sizeof(double)));
    wo->padfDstNoDataReal[0] = kNoData;
    char** o = nullptr;
    o = CSLSetNameValue(o, "INIT_DEST", "NO_DATA");
    // A window wholly outside the source stays kNoData rather than failing.
    o = CSLSetNameValue(o, "ERROR_OUT_IF_EMPTY_SOURCE_WINDOW", "NO");
    o = CSLSetNameValue(o, "XSCALE", number(x_scale_).c_str());
    o = CSLSetNameValue(o, "YSCALE", number(y_scale_).c_str());
    wo->papszWarpOptions = o;
    wo->pfnTransformer = lattice_transform;
    wo->pTransformerArg = &lattice;
    CPLErrorReset();
    GDALWarpOperationH op = GDALCreateWarpOperation(wo);
    GDALDestroyWarpOptions(wo); // the operation holds a copy; the transformer is ours
    if (!op) throw Error(subject_, "cannot reproject raster: " + gdal::last_error("bad warp options"));
    const CPLErr e = GDALWarpRegionToBuffer(op, 0, 0, cols, rows, out, GDT_Float32, 0, 0, 0, 0);
    GDALDestroyWarpOperation(op);
    if (e != CE_None) throw Error(subject_, "cannot reproject raster: " + gdal::last_error("warp failed"));
}

bool MetricWarp::exact_position(double x, double y, double& sx, double& sy) const {
    double z = 0;
    int ok = 0;
    sx = x;
    sy = y;
    GDALGenImgProjTransform(exact_, TRUE, 1, &sx, &sy, &z, &ok);
    return ok != 0;
}

bool MetricWarp::lattice_position(double x, double y, double& sx, double& sy) const {
    const int col = int(std::floor(x)), row = int(std::floor(y));
    const Lattice l = lattice_around(exact_, row, col, 1, 1);
    return l.at(x, y, sx, sy);
}

} // namespace overflight
