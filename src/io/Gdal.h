#pragma once
// Private to src/io: GDAL set-up and ownership. GDAL is used through its C
// API; these wrappers give datasets RAII ownership, register the drivers once,
// silence GDAL's own stderr messages (Overflight reports every failure as one
// Error line instead) and turn the last GDAL error into that line.
#include <gdal.h>
#include <gdal_utils.h>

#include <memory>
#include <string>
#include <vector>

namespace overflight::gdal {

// Registers all drivers and installs CPLQuietErrorHandler, once per process.
void ensure_initialised();

// The last message GDAL recorded on this thread, or `fallback` when it recorded none.
std::string last_error(const std::string& fallback);

struct DatasetCloser {
    void operator()(GDALDatasetH ds) const { if (ds) GDALClose(ds); }
};
using Dataset = std::unique_ptr<void, DatasetCloser>;

// Opens a raster read-only; Error(path, ...) when missing or not a raster GDAL reads.
Dataset open_raster(const std::string& path);

// A MEM dataset of rows x cols x bands of `type`, georeferenced when gt/wkt are
// given; Error(subject, ...) (the file it is made from) when memory runs out.
Dataset create_mem(const std::string& subject, int cols, int rows, int bands, GDALDataType type,
                   const double* geotransform = nullptr, const std::string& wkt = "");

// GDALFillNodata over `band` (its no-data value marks the voids) searching up
// to `distance` samples, with its work planes in memory: its default is LZW
// GeoTIFFs in the working directory (or CPL_TMPDIR) written and read back on
// every call; the same algorithm on the same numbers gives the same fill.
// Error(subject, "cannot fill no-data: ...") on failure.
void fill_nodata(GDALRasterBandH band, int distance, const std::string& subject);

// GDALTranslate / GDALWarp to an in-memory dataset with gdal_translate /
// gdalwarp command-line options (the "-of MEM" is added here). Error(subject, ...) on failure.
Dataset translate(GDALDatasetH src, const std::vector<std::string>& options, const std::string& subject);
// As translate, to a virtual dataset (VRT) that reads `src` (which must outlive
// it) only when its pixels are read: a raster larger than memory passes through.
Dataset translate_lazily(GDALDatasetH src, const std::vector<std::string>& options, const std::string& subject);
Dataset warp(GDALDatasetH src, const std::vector<std::string>& options, const std::string& subject);

// The output grid gdalwarp would make for `src` reprojected to `dst_wkt`
// (empty: its own CRS), from GDAL's general image projection transformer
// (GDALSuggestedWarpOutput2: the source's resolution carried over), and that
// transformer from the source's pixels. Error(subject, problem + ": " +
// GDAL's message) when there is no transformation or no grid.
class SuggestedWarpOutput {
public:
    SuggestedWarpOutput(GDALDatasetH src, const std::string& dst_wkt, const std::string& subject,
                        const std::string& problem);
    ~SuggestedWarpOutput();
    SuggestedWarpOutput(const SuggestedWarpOutput&) = delete;
    SuggestedWarpOutput& operator=(const SuggestedWarpOutput&) = delete;

    double geotransform[6] = {};
    int cols = 0, rows = 0;
    // For GDALGenImgProjTransform; valid while this object lives.
    void* transformer() const { return transformer_; }

private:
    void* transformer_ = nullptr;
};

} // namespace overflight::gdal
