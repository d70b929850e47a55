// Based on: Szenberg 1997, sec. 5.2, eq. 7, Algorithm 2. See DepthVector.h.
#include "raycast/DepthVector.h"

namespace overflight {

void depth_vector(const Camera& camera, double first, double step, int count, std::vector<float>& out) {
    out.resize(std::size_t(count > 0 ? count : 0));
    const double n = camera.near, f = camera.far;
    for (int k = 0; k < count; ++k) {
        const double d = first + step * k;
        out[std::size_t(k)] = float((f - f * n / d) / (f - n));
    }
}

} // namespace overflight
