// Based on: DESIGN sec. 2 and 6 (window depth in [0,1], 1.0 for sky, written
// as float32 TIFF; pictures as PNG).
#include "io/ImageWriters.h"

#include "core/Error.h"
#include "io/Files.h"
#include "io/Gdal.h"

#include <cpl_error.h>

#define STB_IMAGE_WRITE_IMPLEMENTATION
#define STB_IMAGE_WRITE_STATIC
#include <stb/stb_image_write.h>

namespace overflight {

void write_png(const std::string& path, const ColorImage& image) {
    if (image.width < 1 || image.height < 1 || image.pixels.size() != std::size_t(image.width) * std::size_t(image.height))
        throw Error(path, "cannot write an empty or inconsistent image");
    static_assert(sizeof(Rgb8) == 3, "Rgb8 must be packed RGB for stb");
    write_atomically(path, [&](const std::string& temp) {
        if (!stbi_write_png(temp.c_str(), image.width, image.height, 3, image.pixels.data(), image.width * 3))
            throw Error(path, "cannot write PNG (folder not writable or disk full?)");
    });
}

void write_depth_tiff(const std::string& path, const DepthImage& depth) {
    if (depth.width < 1 || depth.height < 1 || depth.pixels.size() != std::size_t(depth.width) * std::size_t(depth.height))
        throw Error(path, "cannot write an empty or inconsistent depth image");
    gdal::ensure_initialised();
    write_atomically(path, [&](const std::string& temp) {
        GDALDriverH gtiff = GDALGetDriverByName("GTiff");
        if (!gtiff) throw Error(path, "GDAL has no GTiff driver");
        const char* options[] = {"COMPRESS=DEFLATE", "PREDICTOR=3", nullptr};
        CPLErrorReset();
        gdal::Dataset ds(GDALCreate(gtiff, temp.c_str(), depth.width, depth.height, 1, GDT_Float32,
                                    const_cast<char**>(options)));
        if (!ds) throw Error(path, "cannot create TIFF: " + gdal::last_error("GDALCreate failed"));
        GDALRasterBandH band = GDALGetRasterBand(ds.get(), 1);
        bool ok = GDALRasterIO(band, GF_Write, 0, 0, depth.width, depth.height, const_cast<float*>(depth.pixels.data()),
                               depth.width, depth.height, GDT_Float32, 0, 0) == CE_None;
        GDALSetDescription(band, "window depth");
        // Closing flushes; a failure there (disk full) must not go unnoticed.
        GDALClose(ds.release());
        ok = ok && CPLGetLastErrorType() < CE_Failure;
        if (!ok) throw Error(path, "cannot write TIFF: " + gdal::last_error("write failed"));
    });
}

} // namespace overflight
