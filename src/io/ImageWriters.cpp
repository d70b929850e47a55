// Based on: DESIGN sec. 2 and 6 (window depth in [0,1], 1.0 for sky, written
// as float32 TIFF; pictures as PNG).
#include "io/ImageWriters.h"

#include "core/Error.h"
#include "io/Files.h"
#include "io/Gdal.h"

#include <cpl_error.h>
#include <cpl_vsi.h>

#include <atomic>
#include <memory>

#define STB_IMAGE_WRITE_IMPLEMENTATION
#define STB_IMAGE_WRITE_STATIC
#include <stb/stb_image_write.h>

namespace overflight {

void write_png(const std::string& path, const ColorImage& image) {
    if (image.width < 1 || image.height < 1 || image.pixels.size() != std::size_t(image.width) * std::size_t(image.height))
        throw Error(path, "cannot write an empty or inconsistent image");
    static_assert(sizeof(Rgb8) == 3, "Rgb8 must be packed RGB for stb");
    // stbi_write_png ignores the results of fwrite and fclose (a full disk left
    // a truncated PNG): encode through stb's callback into a CheckedFile.
    write_file_atomically(path, [&](CheckedFile& file) {
        const auto sink = [](void* context, void* data, int size) {
            static_cast<CheckedFile*>(context)->write(data, std::size_t(size));
        };
        if (!stbi_write_png_to_func(sink, &file, image.width, image.height, 3, image.pixels.data(), image.width * 3))
            throw Error(path, "cannot encode PNG (out of memory)");
    });
}

void write_depth_tiff(const std::string& path, const DepthImage& depth) {
    if (depth.width < 1 || depth.height < 1 || depth.pixels.size() != std::size_t(depth.width) * std::size_t(depth.height))
        throw Error(path, "cannot write an empty or inconsistent depth image");
    check_output_folder(path);
    gdal::ensure_initialised();
    // GDAL encodes the TIFF in memory (/vsimem/): libtiff's write errors
    // reach GDAL only as warnings or not at all, so the bytes go to disk
    // through a CheckedFile, which reports a full disk as such.
    static std::atomic<unsigned> counter{0};
    const std::string mem_name = "/vsimem/overflight-depth-" + std::to_string(counter++) + ".tif";
    GDALDriverH gtiff = GDALGetDriverByName("GTiff");
    if (!gtiff) throw Error(path, "GDAL has no GTiff driver");
    const char* options[] = {"COMPRESS=DEFLATE", "PREDICTOR=3", nullptr};
    CPLErrorReset();
    gdal::Dataset ds(GDALCreate(gtiff, mem_name.c_str(), depth.width, depth.height, 1, GDT_Float32,
                                const_cast<char**>(options)));
    if (!ds) throw Error(path, "cannot create TIFF: " + gdal::last_error("GDALCreate failed"));
    GDALRasterBandH band = GDALGetRasterBand(ds.get(), 1);
    bool ok = GDALRasterIO(band, GF_Write, 0, 0, depth.width, depth.height, const_cast<float*>(depth.pixels.data()),
                           depth.width, depth.height, GDT_Float32, 0, 0) == CE_None;
    GDALSetDescription(band, "window depth");
    GDALClose(ds.release());
    ok = ok && CPLGetLastErrorType() < CE_Failure;
    vsi_l_offset size = 0;
    // TRUE: the buffer is handed over (and the in-memory file removed).
    const std::unique_ptr<GByte, decltype(&VSIFree)> bytes(VSIGetMemFileBuffer(mem_name.c_str(), &size, TRUE),
                                                           &VSIFree);
    if (!ok || !bytes) throw Error(path, "cannot encode TIFF: " + gdal::last_error("GDAL failed"));
    write_file_atomically(path, [&](CheckedFile& file) { file.write(bytes.get(), std::size_t(size)); });
}

} // namespace overflight
