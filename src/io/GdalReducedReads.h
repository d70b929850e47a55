#pragma once
// Private to src/io (it includes GDAL's headers): reading a raster band at
// less than its full resolution without ever holding it whole, for rasters
// larger than memory or than a direct render needs.
//
// Based on: GDAL's RasterIO model (a window read into a smaller buffer is
// resampled, through the band's overviews when they are fine enough) and its
// approximate statistics (GDALComputeRasterStatistics with bApproxOK: whole
// blocks spread over the raster, or an overview).
#include <gdal.h>

#include <functional>
#include <string>
#include <vector>

namespace overflight::gdal {

// Reads the top-left (factor*cols_out) x (factor*rows_out) window of band 1
// of the raster at `path` into `out` (cols_out x rows_out floats, row-major),
// each output sample the mean of its factor x factor block of source samples
// (GDAL's average resampling: no-data samples are left out of the mean, a
// block of no-data only is the band's no-data value). GDAL streams the window
// through its block cache (bounded memory) and reads an overview instead when
// the band has one at least as fine as the output. Strips of rows are read in
// parallel, each through its own handle of `path` (a GDAL dataset handle is
// not thread-safe); each output sample depends on its block alone, so the
// result is that of one read. factor >= 1; cols_out, rows_out >= 1 and the
// window inside the band. Error(subject, ...) when memory or a read fails.
void read_block_averages(const std::string& path, int factor, int cols_out, int rows_out, std::vector<float>& out,
                         const std::string& subject);

// Calls visit(col, row, value) for about `budget` samples of `band` spread
// over the whole raster, in full-resolution coordinates: the samples of the
// smallest overview holding at least `budget` samples when the band has
// overviews, else whole blocks (each decoded once) every k-th block row and
// column, k chosen so that about `budget` samples are read; every sample when
// the raster holds at most `budget`. Returns how the sample was taken, e.g.
// "64 of 6241 blocks of 256x256" or "overview 2500x2500" or "every sample".
// Error(subject, ...) when a read fails.
std::string sample_band(GDALRasterBandH band, long long budget, const std::function<void(int, int, float)>& visit,
                        const std::string& subject);

} // namespace overflight::gdal
