// Map coordinates through GDAL/PROJ. See MapFrame.h.
#include "MapFrame.h"

#include "Gdal.h"
#include "core/Error.h"

#include <ogr_spatialref.h>

#include <cmath>

namespace overflight {

namespace {

struct TransformDeleter {
    void operator()(OGRCoordinateTransformation* t) const { OGRCoordinateTransformation::DestroyCT(t); }
};
using Transform = std::unique_ptr<OGRCoordinateTransformation, TransformDeleter>;

Transform make_transform(const OGRSpatialReference& from, const OGRSpatialReference& to) {
    return Transform(OGRCreateCoordinateTransformation(&from, &to));
}

// (a, b) through `t`, or false when PROJ cannot transform it.
bool apply(const OGRCoordinateTransformation& t, double& a, double& b) {
    double x = a, y = b;
    if (!const_cast<OGRCoordinateTransformation&>(t).Transform(1, &x, &y) || !std::isfinite(x) || !std::isfinite(y))
        return false;
    a = x;
    b = y;
    return true;
}

} // namespace

struct MapFrame::Transforms {
    OGRSpatialReference terrain, lonlat;
    Transform to_lonlat, from_lonlat;
};

MapFrame::MapFrame(const TerrainInfo& info, double h_scale, const std::string& subject)
    : grid_(info.geotransform, h_scale), t_(std::make_unique<Transforms>()) {
    if (!info.georeferenced || info.crs_wkt.empty())
        throw Error(subject, "the terrain " + info.source +
                                 " has no georeferencing (CRS); give engine coordinates X,Z (metres from its first sample)");
    gdal::ensure_initialised();
    t_->terrain.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
    t_->lonlat.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
    if (t_->terrain.importFromWkt(info.crs_wkt.c_str()) != OGRERR_NONE || t_->lonlat.importFromEPSG(4326) != OGRERR_NONE)
        throw Error(subject, "the CRS of " + info.source + " is not one GDAL reads");
    t_->to_lonlat = make_transform(t_->terrain, t_->lonlat);
    t_->from_lonlat = make_transform(t_->lonlat, t_->terrain);
    if (!t_->to_lonlat || !t_->from_lonlat)
        throw Error(subject, "PROJ has no transformation between the CRS of " + info.source + " and WGS 84");
    if (const char* name = t_->terrain.GetName()) name_ = name;
    const char* authority = t_->terrain.GetAuthorityName(nullptr);
    const char* code = t_->terrain.GetAuthorityCode(nullptr);
    if (authority && code) code_ = std::string(authority) + ":" + code;
}

MapFrame::~MapFrame() = default;

glm::dvec2 MapFrame::world_of(double a, double b, const std::string& crs, const std::string& subject) const {
    if (!crs.empty()) {
        const std::string point = std::to_string(a) + "," + std::to_string(b);
        if (crs == kLonLat) {
            if (!apply(*t_->from_lonlat, a, b))
                throw Error(subject, "longitude, latitude " + point + " cannot be transformed to " + name_);
        } else {
            OGRSpatialReference user;
            user.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
            if (user.SetFromUserInput(crs.c_str()) != OGRERR_NONE)
                throw Error(subject, "'" + crs + "' is not a CRS GDAL knows (for example EPSG:4326)");
            const Transform t = make_transform(user, t_->terrain);
            if (!t) throw Error(subject, "PROJ has no transformation from " + crs + " to " + name_);
            if (!apply(*t, a, b)) throw Error(subject, "point " + point + " in " + crs + " cannot be transformed to " + name_);
        }
    }
    return grid_.world_of_map(a, b);
}

glm::dvec2 MapFrame::map_of_world(double x, double z) const { return grid_.map_of_world(x, z); }

glm::dvec2 MapFrame::lonlat_of_world(double x, double z) const {
    glm::dvec2 p = grid_.map_of_world(x, z);
    if (!apply(*t_->to_lonlat, p.x, p.y)) return {NAN, NAN};
    return p;
}

} // namespace overflight
