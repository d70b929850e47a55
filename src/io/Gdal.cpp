#include "io/Gdal.h"

#include "core/Error.h"

#include <cpl_conv.h>
#include <cpl_error.h>
#include <cpl_string.h>
#include <gdal_alg.h>
#include <ogr_srs_api.h>

#include <cerrno>
#include <cmath>
#include <cstring>
#include <fcntl.h>
#include <filesystem>
#include <memory>
#include <mutex>
#include <unistd.h>

namespace overflight::gdal {

namespace {

// CSL string list owned for the duration of one GDAL utility call.
struct StringList {
    char** list = nullptr;
    explicit StringList(const std::vector<std::string>& items) {
        for (const std::string& s : items) list = CSLAddString(list, s.c_str());
    }
    ~StringList() { CSLDestroy(list); }
    StringList(const StringList&) = delete;
    StringList& operator=(const StringList&) = delete;
};

std::vector<std::string> with_mem_output(const std::vector<std::string>& options) {
    std::vector<std::string> all{"-of", "MEM"};
    all.insert(all.end(), options.begin(), options.end());
    return all;
}

} // namespace

void ensure_initialised() {
    static std::once_flag once;
    std::call_once(once, [] {
        CPLSetErrorHandler(CPLQuietErrorHandler);
        // GDALFillNodata keeps its work rasters in temporary files named by
        // CPLGenerateTempFilename, in the current folder unless CPL_TMPDIR is
        // set: a run stopped there would leave them beside the user's files.
        if (!CPLGetConfigOption("CPL_TMPDIR", nullptr)) {
            std::error_code ec;
            const std::filesystem::path tmp = std::filesystem::temp_directory_path(ec);
            if (!ec) CPLSetConfigOption("CPL_TMPDIR", tmp.c_str());
        }
        GDALAllRegister();
    });
}

std::string last_error(const std::string& fallback) {
    const char* msg = CPLGetLastErrorMsg();
    if (!msg || !*msg) return fallback;
    std::string s(msg);
    // One line per error: GDAL messages sometimes span several.
    for (char& c : s)
        if (c == '\n' || c == '\r') c = ' ';
    return s;
}

Dataset open_raster(const std::string& path) {
    ensure_initialised();
    std::error_code ec;
    if (!std::filesystem::exists(path, ec)) throw Error(path, "no such file");
    // GDAL reports a file it may not open as an unrecognised format: ask the
    // system first, so that the user hears the real reason.
    const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
    if (fd < 0) {
        if (errno == EACCES || errno == EPERM) throw Error(path, "permission denied");
        throw Error(path, std::string("cannot open: ") + std::strerror(errno));
    }
    ::close(fd);
    CPLErrorReset();
    Dataset ds(GDALOpenEx(path.c_str(), GDAL_OF_RASTER | GDAL_OF_READONLY, nullptr, nullptr, nullptr));
    if (!ds) throw Error(path, "not a raster GDAL can read (" + last_error("unrecognised format") + ")");
    if (GDALGetRasterCount(ds.get()) < 1) throw Error(path, "has no raster band");
    return ds;
}

Dataset create_mem(const std::string& subject, int cols, int rows, int bands, GDALDataType type,
                   const double* geotransform, const std::string& wkt) {
    ensure_initialised();
    GDALDriverH mem = GDALGetDriverByName("MEM");
    Dataset ds(GDALCreate(mem, "", cols, rows, bands, type, nullptr));
    if (!ds)
        throw Error(subject, "not enough memory for a temporary " + std::to_string(cols) + "x" + std::to_string(rows) +
                                 " raster");
    if (geotransform) GDALSetGeoTransform(ds.get(), const_cast<double*>(geotransform));
    if (!wkt.empty()) GDALSetProjection(ds.get(), wkt.c_str());
    return ds;
}

void fill_nodata(GDALRasterBandH band, int distance, const std::string& subject) {
    const std::unique_ptr<char*, decltype(&CSLDestroy)> options(CSLSetNameValue(nullptr, "TEMP_FILE_DRIVER", "MEM"),
                                                                &CSLDestroy);
    CPLErrorReset();
    if (GDALFillNodata(band, nullptr, double(distance), 0, 0, options.get(), nullptr, nullptr) != CE_None)
        throw Error(subject, "cannot fill no-data: " + last_error("GDALFillNodata failed"));
}

namespace {

Dataset translate_to(const std::string& format, GDALDatasetH src, const std::vector<std::string>& options,
                     const std::string& subject) {
    std::vector<std::string> all{"-of", format};
    all.insert(all.end(), options.begin(), options.end());
    StringList args(all);
    GDALTranslateOptions* opts = GDALTranslateOptionsNew(args.list, nullptr);
    if (!opts) throw Error(subject, "bad translate options: " + last_error("?"));
    CPLErrorReset();
    int usage_error = 0;
    Dataset out(GDALTranslate("", src, opts, &usage_error));
    GDALTranslateOptionsFree(opts);
    if (!out || usage_error) throw Error(subject, "cannot convert raster: " + last_error("GDALTranslate failed"));
    return out;
}

} // namespace

Dataset translate(GDALDatasetH src, const std::vector<std::string>& options, const std::string& subject) {
    return translate_to("MEM", src, options, subject);
}

Dataset translate_lazily(GDALDatasetH src, const std::vector<std::string>& options, const std::string& subject) {
    return translate_to("VRT", src, options, subject);
}

Dataset warp(GDALDatasetH src, const std::vector<std::string>& options, const std::string& subject) {
    StringList args(with_mem_output(options));
    GDALWarpAppOptions* opts = GDALWarpAppOptionsNew(args.list, nullptr);
    if (!opts) throw Error(subject, "bad warp options: " + last_error("?"));
    CPLErrorReset();
    int usage_error = 0;
    GDALDatasetH srcs[1] = {src};
    Dataset out(GDALWarp("", nullptr, 1, srcs, opts, &usage_error));
    GDALWarpAppOptionsFree(opts);
    if (!out || usage_error) throw Error(subject, "cannot reproject raster: " + last_error("GDALWarp failed"));
    return out;
}

SuggestedWarpOutput::SuggestedWarpOutput(GDALDatasetH src, const std::string& dst_wkt, const std::string& subject,
                                         const std::string& problem) {
    char** to = dst_wkt.empty() ? nullptr : CSLSetNameValue(nullptr, "DST_SRS", dst_wkt.c_str());
    CPLErrorReset();
    transformer_ = GDALCreateGenImgProjTransformer2(src, nullptr, to);
    CSLDestroy(to);
    if (!transformer_) throw Error(subject, problem + ": " + last_error("no transformation to the target CRS"));
    double extent[4];
    const CPLErr e = GDALSuggestedWarpOutput2(src, GDALGenImgProjTransform, transformer_, geotransform, &cols, &rows,
                                              extent, 0);
    if (e != CE_None || !(std::abs(geotransform[1]) > 0)) {
        GDALDestroyGenImgProjTransformer(transformer_);
        throw Error(subject, problem + ": " + last_error("no suggested output grid"));
    }
}

SuggestedWarpOutput::~SuggestedWarpOutput() { GDALDestroyGenImgProjTransformer(transformer_); }

} // namespace overflight::gdal
