// The affine transform between the engine's world frame and a grid's map
// coordinates. See GridGeoreference.h.
#include "GridGeoreference.h"

namespace overflight {

GridGeoreference::GridGeoreference(const std::array<double, 6>& gt, double h_scale) : gt_(gt), h_scale_(h_scale) {
    // Inverse of [x y] = [gt0 gt3] + [[gt1 gt2] [gt4 gt5]] [col row], as GDALInvGeoTransform.
    const double det = gt[1] * gt[5] - gt[2] * gt[4];
    const double a = gt[5] / det, b = -gt[2] / det, c = -gt[4] / det, d = gt[1] / det;
    inverse_ = {-gt[0] * a - gt[3] * b, a, b, -gt[0] * c - gt[3] * d, c, d};
}

glm::dvec2 GridGeoreference::map_of_world(double x, double z) const {
    const double col = x / h_scale_ + 0.5, row = z / h_scale_ + 0.5;
    return {gt_[0] + col * gt_[1] + row * gt_[2], gt_[3] + col * gt_[4] + row * gt_[5]};
}

glm::dvec2 GridGeoreference::world_of_map(double easting, double northing) const {
    const double col = inverse_[0] + easting * inverse_[1] + northing * inverse_[2];
    const double row = inverse_[3] + easting * inverse_[4] + northing * inverse_[5];
    return {(col - 0.5) * h_scale_, (row - 0.5) * h_scale_};
}

} // namespace overflight
