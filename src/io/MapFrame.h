#pragma once
// Positions on a georeferenced terrain in map terms (DESIGN sec. 6.1): in the
// terrain's own CRS, in longitude/latitude (WGS 84), or in any CRS GDAL/PROJ
// knows (EPSG:n, WKT, a PROJ string), converted to and from the engine's world
// frame (X east, Z south, DESIGN sec. 1) through the grid's geotransform
// (core/GridGeoreference.h). Axis order is always easting/longitude first
// (GDAL's OAMS_TRADITIONAL_GIS_ORDER), whatever the CRS's own order says.
#include "core/DataSet.h"
#include "core/GridGeoreference.h"

#include <glm/vec2.hpp>

#include <memory>
#include <string>

namespace overflight {

// The CRS name a user writes for longitude/latitude on WGS 84.
inline constexpr const char* kLonLat = "lonlat";

class MapFrame {
public:
    // The frame of a terrain loaded with `info` and horizontal scale h_scale.
    // Throws Error(subject, ...) when the terrain has no georeferencing or no CRS.
    MapFrame(const TerrainInfo& info, double h_scale, const std::string& subject);
    ~MapFrame();
    MapFrame(const MapFrame&) = delete;
    MapFrame& operator=(const MapFrame&) = delete;

    // World (X, Z) of the point (a, b) given in `crs`: empty = the terrain's
    // CRS, kLonLat = longitude, latitude on WGS 84, else any definition
    // OGRSpatialReference::SetFromUserInput reads. Throws Error(subject, ...)
    // for a CRS GDAL does not know or a point PROJ cannot transform.
    glm::dvec2 world_of(double a, double b, const std::string& crs, const std::string& subject) const;
    // Map coordinates of world (X, Z) in the terrain's CRS and in WGS 84 longitude, latitude.
    glm::dvec2 map_of_world(double x, double z) const;
    glm::dvec2 lonlat_of_world(double x, double z) const;

    // "WGS 84 / UTM zone 10N"; "EPSG:32610" (empty when the CRS has no EPSG code).
    const std::string& crs_name() const { return name_; }
    const std::string& crs_code() const { return code_; }

private:
    struct Transforms;
    GridGeoreference grid_;
    std::unique_ptr<Transforms> t_;
    std::string name_, code_;
};

} // namespace overflight
