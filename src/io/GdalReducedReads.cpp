#include "io/GdalReducedReads.h"

#include "core/Error.h"
#include "io/Gdal.h"

#include <cpl_error.h>

#include <algorithm>
#include <cmath>
#include <new>
#include <thread>

#include <tbb/parallel_for.h>

namespace overflight::gdal {

namespace {

void resize_or_throw(std::vector<float>& v, long long n, int cols, int rows, const std::string& subject) {
    try {
        v.resize(std::size_t(n));
    } catch (const std::bad_alloc&) {
        throw Error(subject, "not enough memory for a " + std::to_string(cols) + "x" + std::to_string(rows) + " raster");
    }
}

void read_window(GDALRasterBandH band, int x, int y, int w, int h, int buf_w, int buf_h, float* buf,
                 GDALRIOResampleAlg resampling, const std::string& subject) {
    GDALRasterIOExtraArg extra;
    INIT_RASTERIO_EXTRA_ARG(extra);
    extra.eResampleAlg = resampling;
    CPLErrorReset();
    if (GDALRasterIOEx(band, GF_Read, x, y, w, h, buf, buf_w, buf_h, GDT_Float32, 0, 0, &extra) != CE_None)
        throw Error(subject, "unreadable raster: " + last_error("read failed"));
}

} // namespace

void read_block_averages(const std::string& path, int factor, int cols_out, int rows_out, std::vector<float>& out,
                         const std::string& subject) {
    resize_or_throw(out, (long long)cols_out * rows_out, cols_out, rows_out, subject);
    // Strips of whole source blocks' worth of rows keep each task's reads
    // apart; several strips per core balance uneven decoding costs.
    const int strips = std::clamp(rows_out / 64, 1, 4 * int(std::thread::hardware_concurrency()));
    tbb::parallel_for(0, strips, [&](int s) {
        const int r0 = int((long long)rows_out * s / strips), r1 = int((long long)rows_out * (s + 1) / strips);
        if (r1 <= r0) return;
        Dataset ds = open_raster(path);
        read_window(GDALGetRasterBand(ds.get(), 1), 0, r0 * factor, cols_out * factor, (r1 - r0) * factor, cols_out,
                    r1 - r0, out.data() + std::size_t(r0) * std::size_t(cols_out),
                    factor == 1 ? GRIORA_NearestNeighbour : GRIORA_Average, subject);
    });
}

std::string sample_band(GDALRasterBandH band, long long budget, const std::function<void(int, int, float)>& visit,
                        const std::string& subject) {
    const int cols = GDALGetRasterBandXSize(band), rows = GDALGetRasterBandYSize(band);
    std::vector<float> buf;
    if ((long long)cols * rows <= budget) {
        resize_or_throw(buf, (long long)cols * rows, cols, rows, subject);
        read_window(band, 0, 0, cols, rows, cols, rows, buf.data(), GRIORA_NearestNeighbour, subject);
        for (int r = 0; r < rows; ++r)
            for (int c = 0; c < cols; ++c) visit(c, r, buf[std::size_t(r) * cols + c]);
        return "every sample";
    }
    if (GDALGetOverviewCount(band) > 0) {
        GDALRasterBandH ov = GDALGetRasterSampleOverviewEx(band, GUIntBig(budget));
        if (ov && ov != band) {
            const int ow = GDALGetRasterBandXSize(ov), oh = GDALGetRasterBandYSize(ov);
            resize_or_throw(buf, (long long)ow * oh, ow, oh, subject);
            read_window(ov, 0, 0, ow, oh, ow, oh, buf.data(), GRIORA_NearestNeighbour, subject);
            for (int r = 0; r < oh; ++r)
                for (int c = 0; c < ow; ++c)
                    visit(int((c + 0.5) * cols / ow), int((r + 0.5) * rows / oh), buf[std::size_t(r) * ow + c]);
            return "overview " + std::to_string(ow) + "x" + std::to_string(oh);
        }
    }
    // Whole blocks, so each block read is decoded once (as GDAL's approximate
    // statistics do), every k-th block row and column; a band stored in whole
    // rows (strips) is sampled every k-th row band.
    int bw = 0, bh = 0;
    GDALGetBlockSize(band, &bw, &bh);
    bw = std::clamp(bw, 1, cols);
    bh = std::clamp(bh, 1, rows);
    const long long nbx = (cols + bw - 1) / bw, nby = (rows + bh - 1) / bh;
    const long long wanted = std::max(1LL, budget / ((long long)bw * bh));
    long long kx = 1, ky = 1;
    if (nbx == 1) {
        ky = std::max(1LL, (nby + wanted - 1) / wanted);
    } else {
        const long long k = std::max(1LL, (long long)std::ceil(std::sqrt(double(nbx * nby) / double(wanted))));
        kx = std::min(k, nbx);
        ky = std::max(1LL, (long long)std::ceil(double(nbx * nby) / double(wanted) / double(kx)));
        ky = std::min(ky, nby);
    }
    resize_or_throw(buf, (long long)bw * bh, bw, bh, subject);
    long long blocks = 0;
    for (long long by = ky / 2; by < nby; by += ky)
        for (long long bx = kx / 2; bx < nbx; bx += kx) {
            const int x0 = int(bx * bw), y0 = int(by * bh);
            const int w = std::min(bw, cols - x0), h = std::min(bh, rows - y0);
            read_window(band, x0, y0, w, h, w, h, buf.data(), GRIORA_NearestNeighbour, subject);
            for (int r = 0; r < h; ++r)
                for (int c = 0; c < w; ++c) visit(x0 + c, y0 + r, buf[std::size_t(r) * w + c]);
            ++blocks;
        }
    return std::to_string(blocks) + " of " + std::to_string(nbx * nby) + " blocks of " + std::to_string(bw) + "x" +
           std::to_string(bh);
}

} // namespace overflight::gdal
