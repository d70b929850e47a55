#pragma once
// Where a terrain grid lies in its map (DESIGN sec. 1 and 4): GDAL's affine
// geotransform of the grid as loaded and the engine's world frame. Sample
// (row i, col j) is the raster pixel whose top-left corner is
// (gt[0] + j gt[1] + i gt[2], gt[3] + j gt[4] + i gt[5]); its value stands at
// the pixel's centre, which is the world point X = hs j, Z = hs i. So a world
// point (X, Z) is at pixel coordinates (X / hs + 0.5, Z / hs + 0.5) and its map
// coordinates follow from the affine transform (GDAL's GDALApplyGeoTransform).
#include <glm/vec2.hpp>

#include <array>

namespace overflight {

class GridGeoreference {
public:
    // `geotransform` must be invertible (non-zero determinant), h_scale > 0.
    GridGeoreference(const std::array<double, 6>& geotransform, double h_scale);

    // Map coordinates (easting, northing in the grid's CRS units) of world (X, Z).
    glm::dvec2 map_of_world(double x, double z) const;
    // World (X, Z) of map coordinates (easting, northing): inverse of map_of_world.
    glm::dvec2 world_of_map(double easting, double northing) const;

private:
    std::array<double, 6> gt_;
    std::array<double, 6> inverse_; // map -> pixel coordinates
    double h_scale_;
};

} // namespace overflight
