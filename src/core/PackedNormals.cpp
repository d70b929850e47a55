#include "core/PackedNormals.h"

#include "core/Parallel.h"

#include <algorithm>
#include <cmath>

namespace overflight {

std::uint32_t PackedNormals::pack(const glm::vec3& n) {
    const auto q = [](float v, float lo) { return int(std::lround(std::clamp(v, lo, 1.0f) * kScale)); };
    return (std::uint32_t(q(n.x, -1.0f)) & 0x7ffu) | (std::uint32_t(q(n.y, 0.0f)) << 11) |
           (std::uint32_t(q(n.z, -1.0f)) << 21);
}

PackedNormals pack_normals(const Terrain& t) {
    PackedNormals out;
    out.packed.resize(std::size_t(t.rows()) * std::size_t(t.cols()));
    parallel::for_each_index(0, t.rows(), [&](int row) {
        for (int col = 0; col < t.cols(); ++col) out.packed[t.index(row, col)] = PackedNormals::pack(t.sample_normal(row, col));
    });
    return out;
}

} // namespace overflight
