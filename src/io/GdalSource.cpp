#include "io/GdalSource.h"

#include "core/Error.h"
#include "io/Gdal.h"
#include "io/UsgsDemHeader.h"

#include <cpl_conv.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <filesystem>

namespace overflight {

std::string usgs_record_a_text(const std::string& path) {
    std::string head(1024, ' ');
    if (FILE* f = std::fopen(path.c_str(), "rb")) {
        head.resize(std::fread(head.data(), 1, head.size(), f));
        std::fclose(f);
    }
    return head;
}

void check_declared_size(GDALDatasetH ds, const std::string& path, int max_side) {
    GDALDriverH driver = GDALGetDatasetDriver(ds);
    if (driver && std::string(GDALGetDriverShortName(driver)) == "USGSDEM") {
        // GDAL sizes the grid by Record A's profile count; each profile needs a
        // Record B in the file (USGS DEM Standards Part 2).
        const long profiles = usgs_profile_count(usgs_record_a_text(path));
        std::error_code ec;
        const auto bytes = std::filesystem::file_size(path, ec);
        if (max_side > 0 && profiles > max_side)
            throw Error(path, "Record A declares " + std::to_string(profiles) + " profiles, more than " +
                                  std::to_string(max_side));
        if (!ec && profiles > 0 && (long long)bytes < usgs_minimum_file_size(profiles))
            throw Error(path, "Record A declares " + std::to_string(profiles) + " profiles but the file holds only " +
                                  std::to_string(bytes) + " bytes (at least " +
                                  std::to_string(kUsgsRecordBHeaderBytes) + " per profile)");
    }
    const int cols = GDALGetRasterXSize(ds), rows = GDALGetRasterYSize(ds);
    if (rows < 2 || cols < 2)
        throw Error(path, "raster is " + std::to_string(cols) + "x" + std::to_string(rows) +
                              ", a terrain needs at least 2x2 samples");
    if (max_side > 0 && (rows > max_side || cols > max_side))
        throw Error(path, "raster is " + std::to_string(cols) + "x" + std::to_string(rows) + ", more than " +
                              std::to_string(max_side) + " samples per side");
}

void append_band_warnings(GDALDatasetH ds, std::vector<std::string>& warnings) {
    const int bands = GDALGetRasterCount(ds);
    GDALRasterBandH first = GDALGetRasterBand(ds, 1);
    const GDALColorInterp ci = GDALGetRasterColorInterpretation(first);
    std::string interpretation = GDALGetColorInterpretationName(ci);
    for (char& c : interpretation) c = char(std::tolower(static_cast<unsigned char>(c)));
    if (GDALGetRasterColorTable(first) != nullptr)
        warnings.push_back("band 1 is a palette image: its color indices are taken as heights");
    else if (bands > 1)
        warnings.push_back("has " + std::to_string(bands) + " bands; band 1 (" + interpretation + ") is taken as heights" +
                           (ci == GCI_RedBand ? " (an RGB image? give heights as TERRAIN and the image as --color)" : ""));
}

std::vector<std::string> metric_warp_options() {
    char nodata[32];
    std::snprintf(nodata, sizeof nodata, "%.9g", double(kNoData));
    return {"-r", "bilinear", "-dstnodata", nodata, "-ot", "Float32", "-wo", "INIT_DEST=NO_DATA"};
}

double metres_per_unit(const std::string& unit, std::string& name) {
    std::string u = unit;
    for (char& ch : u) ch = char(std::tolower(static_cast<unsigned char>(ch)));
    if (u.empty() || u == "m" || u == "metre" || u == "meter" || u == "metres" || u == "meters") {
        name = "metre";
        return 1.0;
    }
    if (u == "us-ft" || u == "ftus" || u == "us survey foot" || u == "us_survey_foot" || u == "foot_us" ||
        u == "us foot" || u == "survey foot") {
        name = "US survey foot";
        return 1200.0 / 3937.0;
    }
    if (u == "ft" || u == "foot" || u == "feet" || u == "international foot" || u == "intl foot") {
        name = "foot";
        return 0.3048;
    }
    if (u == "cm" || u == "centimetre" || u == "centimeter") {
        name = "centimetre";
        return 0.01;
    }
    name = unit + " (unknown, taken as metres)";
    return 1.0;
}

std::string to_wkt(OGRSpatialReferenceH srs) {
    char* wkt = nullptr;
    OSRExportToWkt(srs, &wkt);
    std::string s = wkt ? wkt : "";
    CPLFree(wkt);
    return s;
}

std::string warped_crs_wkt(const std::string& wkt) {
    if (wkt.empty()) return wkt;
    gdal::Dataset ds = gdal::create_mem("CRS", 1, 1, 1, GDT_Byte, nullptr, wkt);
    const char* reported = GDALGetProjectionRef(ds.get());
    return reported ? reported : "";
}

Srs utm_for(OGRSpatialReferenceH src, double lon, double lat) {
    const int zone = std::clamp(int(std::floor((lon + 180.0) / 6.0)) + 1, 1, 60);
    const bool north = lat >= 0;
    Srs utm(OSRNewSpatialReference(nullptr));
    const char* code = OSRGetAuthorityCode(src, nullptr);
    const char* auth = OSRGetAuthorityName(src, nullptr);
    if (auth && code && std::string(auth) == "EPSG" && std::string(code) == "4326") {
        OSRImportFromEPSG(utm.get(), (north ? 32600 : 32700) + zone);
    } else {
        OSRCopyGeogCSFrom(utm.get(), src);
        OSRSetUTM(utm.get(), zone, north);
        const char* geog = OSRGetAttrValue(src, "GEOGCS", 0);
        const std::string name = std::string(geog ? geog : "unknown") + " / UTM zone " + std::to_string(zone) +
                                 (north ? "N" : "S");
        OSRSetProjCS(utm.get(), name.c_str());
    }
    OSRSetAxisMappingStrategy(utm.get(), OAMS_TRADITIONAL_GIS_ORDER);
    return utm;
}

} // namespace overflight
