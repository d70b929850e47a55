#pragma once
// The crack check of the tile tests: a Röttger mesh over tiles is conforming
// when every edge is shared by two triangles, except on the outline of the
// drawn tiles.
#include "core/MeshArrays.h"

#include <glm/vec3.hpp>

#include <cmath>
#include <set>
#include <tuple>
#include <utility>
#include <vector>

namespace overflight::test {

// Directed edges (XZ) of a triangle list whose reverse is missing, except
// those on the outline of the drawn tiles (the terrain border, or a seam
// towards a tile that is not drawn): cracks or T-junctions.
inline int open_edges(const MeshArrays& m, const std::vector<std::pair<int, int>>& visible, float tw) {
    const std::set<std::pair<int, int>> vis(visible.begin(), visible.end());
    std::set<std::tuple<float, float, float, float>> directed;
    for (std::size_t k = 0; k < m.indices.size(); k += 3)
        for (int e = 0; e < 3; ++e) {
            const glm::vec3 a = m.positions[m.indices[k + e]], b = m.positions[m.indices[k + (e + 1) % 3]];
            directed.insert({a.x, a.z, b.x, b.z});
        }
    int open = 0;
    for (const auto& [px, pz, qx, qz] : directed) {
        if (directed.count({qx, qz, px, pz})) continue;
        const float mx = 0.5f * (px + qx), mz = 0.5f * (pz + qz);
        const int tr = int(mz / tw), tc = int(mx / tw);
        bool outline = false;
        if (px == qx && std::fmod(px, tw) == 0)
            outline = !vis.count({tr, int(px / tw) - 1}) || !vis.count({tr, int(px / tw)});
        if (pz == qz && std::fmod(pz, tw) == 0)
            outline = !vis.count({int(pz / tw) - 1, tc}) || !vis.count({int(pz / tw), tc});
        if (!outline) ++open;
    }
    return open;
}

} // namespace overflight::test
