// Based on: DESIGN sec. 6 (GeoTIFF rasters with georeferencing, as `tile` and `--depth` write them).
#include "io/RasterFile.h"

#include "core/Error.h"
#include "io/Files.h"
#include "io/Gdal.h"

#include <cpl_conv.h>
#include <cpl_error.h>
#include <ogr_srs_api.h>

namespace overflight {

void write_geotiff(const std::string& path, const Image2D<float>& image, const RasterGeoreference& g) {
    if (image.width < 1 || image.height < 1 || image.pixels.size() != std::size_t(image.width) * std::size_t(image.height))
        throw Error(path, "cannot write an empty or inconsistent raster");
    gdal::ensure_initialised();
    std::string wkt;
    if (!g.crs.empty()) {
        OGRSpatialReferenceH srs = OSRNewSpatialReference(nullptr);
        char* text = nullptr;
        const bool ok = OSRSetFromUserInput(srs, g.crs.c_str()) == OGRERR_NONE && OSRExportToWkt(srs, &text) == OGRERR_NONE;
        if (text) wkt = text;
        CPLFree(text);
        OSRDestroySpatialReference(srs);
        if (!ok) throw Error(path, "unknown CRS '" + g.crs + "'");
    }
    write_atomically(path, [&](const std::string& temp) {
        const char* options[] = {"COMPRESS=DEFLATE", nullptr};
        CPLErrorReset();
        gdal::Dataset ds(GDALCreate(GDALGetDriverByName("GTiff"), temp.c_str(), image.width, image.height, 1, GDT_Float32,
                                    const_cast<char**>(options)));
        if (!ds) throw Error(path, "cannot create GeoTIFF: " + gdal::last_error("GDALCreate failed"));
        if (g.geotransform) GDALSetGeoTransform(ds.get(), const_cast<double*>(g.geotransform->data()));
        if (!wkt.empty()) GDALSetProjection(ds.get(), wkt.c_str());
        GDALRasterBandH band = GDALGetRasterBand(ds.get(), 1);
        if (g.nodata) GDALSetRasterNoDataValue(band, *g.nodata);
        if (!g.unit.empty()) GDALSetRasterUnitType(band, g.unit.c_str());
        if (g.scale != 1.0 || g.offset != 0.0) {
            GDALSetRasterScale(band, g.scale);
            GDALSetRasterOffset(band, g.offset);
        }
        float* pixels = const_cast<float*>(image.pixels.data());
        bool ok = GDALRasterIO(band, GF_Write, 0, 0, image.width, image.height, pixels, image.width, image.height,
                               GDT_Float32, 0, 0) == CE_None;
        GDALClose(ds.release());
        ok = ok && CPLGetLastErrorType() < CE_Failure;
        if (!ok) throw Error(path, "cannot write GeoTIFF: " + gdal::last_error("write failed"));
    });
}

Image2D<float> read_raster_band(const std::string& path, int band_index) {
    gdal::Dataset ds = gdal::open_raster(path);
    if (band_index < 1 || band_index > GDALGetRasterCount(ds.get()))
        throw Error(path, "has no band " + std::to_string(band_index));
    Image2D<float> out(GDALGetRasterXSize(ds.get()), GDALGetRasterYSize(ds.get()));
    CPLErrorReset();
    if (GDALRasterIO(GDALGetRasterBand(ds.get(), band_index), GF_Read, 0, 0, out.width, out.height, out.pixels.data(),
                     out.width, out.height, GDT_Float32, 0, 0) != CE_None)
        throw Error(path, "unreadable raster: " + gdal::last_error("read failed"));
    return out;
}

} // namespace overflight
