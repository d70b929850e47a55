#include "io/GdalSource.h"

#include <cpl_conv.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>

namespace overflight {

std::vector<std::string> metric_warp_options() {
    char nodata[32];
    std::snprintf(nodata, sizeof nodata, "%.9g", double(kNoData));
    return {"-r", "bilinear", "-dstnodata", nodata, "-ot", "Float32", "-wo", "INIT_DEST=NO_DATA", "-et", "0"};
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
