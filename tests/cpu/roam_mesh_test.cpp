// Split-only ROAM tessellation (CMSC 23700 project 2a sec. 5, 5.1): conforming meshes,
// the triangle budget, nested errors, the view wedge, the focus point, padding.
#include "core/Error.h"
#include "core/Terrain.h"
#include "lod/RoamMesh.h"

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <numeric>
#include <set>
#include <tuple>
#include <utility>
#include <vector>

using namespace overflight;

namespace {

// Deterministic rough terrain: two swells plus hashed noise, so that every
// bintree level has some error.
Terrain rough(int rows, int cols, float hs = 10.0f) {
    Terrain t(rows, cols, hs, 0.5f);
    for (int i = 0; i < rows; ++i)
        for (int j = 0; j < cols; ++j) {
            std::uint32_t x = std::uint32_t(i) * 73856093u ^ std::uint32_t(j) * 19349663u;
            x ^= x >> 13;
            x *= 0x5bd1e995u;
            x ^= x >> 15;
            const double swell = 600 + 400 * std::sin(i * 0.11) * std::cos(j * 0.07) + 150 * std::sin(i * 0.31 + j * 0.23);
            t.raw(i, j) = std::uint16_t(swell + double(x % 64));
            t.color(i, j) = Rgb8{std::uint8_t(i), std::uint8_t(j), 7};
        }
    return t;
}

// Camera inside the terrain at height, looking along `heading` (shear).
Camera camera_at(double x, double z, double y, double heading, double fov = 60) {
    Camera c;
    c.eye = {x, y, z};
    c.heading = heading;
    c.pitch = -10;
    c.fov = fov;
    c.width = 640;
    c.height = 360;
    c.near = 1;
    c.far = 100000;
    return c;
}

// Camera high above looking steeply down with a tilt: no view wedge, every
// triangle is visible.
Camera camera_above(const Terrain& t) {
    Camera c;
    c.eye = {t.width() * 0.5, 5000.0, t.depth() * 0.5};
    c.pitch = -85;
    c.projection = Projection::Tilt;
    c.far = 100000;
    return c;
}

struct GridPoint {
    int row, col;
    auto operator<=>(const GridPoint&) const = default;
};

GridPoint grid_of(const MeshArrays& m, std::uint32_t i, float hs) {
    return {int(std::lround(m.positions[i].z / hs)), int(std::lround(m.positions[i].x / hs))};
}

// Checks that the mesh is conforming: every edge is shared by exactly two
// triangles (with opposite directions) or lies on the grid border, and no
// mesh vertex lies inside an edge (no T-junction). Also: winding is
// counter-clockwise seen from above.
void expect_conforming(const MeshArrays& m, float hs, int rows, int cols) {
    std::set<GridPoint> verts;
    std::map<std::pair<GridPoint, GridPoint>, int> directed;
    int bad_winding = 0;
    for (std::size_t t = 0; t < m.triangle_count(); ++t) {
        GridPoint p[3];
        for (int k = 0; k < 3; ++k) {
            p[k] = grid_of(m, m.indices[3 * t + std::size_t(k)], hs);
            verts.insert(p[k]);
        }
        // cross(p1 - p0, p2 - p0).y in (x = col, z = row) must be > 0 (normal up).
        const long long cy = (long long)(p[1].row - p[0].row) * (p[2].col - p[0].col) -
                             (long long)(p[1].col - p[0].col) * (p[2].row - p[0].row);
        bad_winding += cy <= 0;
        for (int k = 0; k < 3; ++k) ++directed[{p[k], p[(k + 1) % 3]}];
    }
    EXPECT_EQ(bad_winding, 0);
    int unmatched = 0, duplicated = 0, t_junctions = 0;
    for (const auto& [e, n] : directed) {
        duplicated += n != 1;
        const auto [a, b] = e;
        const bool on_border = (a.row == b.row && (a.row == 0 || a.row == rows - 1)) ||
                               (a.col == b.col && (a.col == 0 || a.col == cols - 1));
        if (!on_border && !directed.count({b, a})) ++unmatched;
        const int dr = b.row - a.row, dc = b.col - a.col;
        const int g = std::gcd(std::abs(dr), std::abs(dc));
        for (int k = 1; k < g; ++k) t_junctions += verts.count({a.row + k * dr / g, a.col + k * dc / g}) != 0;
    }
    EXPECT_EQ(duplicated, 0);
    EXPECT_EQ(unmatched, 0);
    EXPECT_EQ(t_junctions, 0);
}

} // namespace

// At a budget of every half cell the bintree is the full-resolution `mesh`
// surface of DESIGN sec. 3: cell (i, j) is cut from (i, j) to (i+1, j+1) when
// i + j is even, from (i, j+1) to (i+1, j) otherwise.
TEST(RoamMesh, FullBudgetGivesTheCheckerboardMesh) {
    const Terrain t = rough(17, 17);
    RoamMesh roam(t);
    const RoamStats s = roam.tessellate(camera_above(t), 2 * 16 * 16);
    ASSERT_EQ(s.triangles, 512u);
    EXPECT_EQ(s.max_level, 8);
    EXPECT_EQ(s.max_error_px, 0.0);
    MeshArrays m;
    roam.write_mesh(m);
    ASSERT_EQ(m.positions.size(), 17u * 17u);
    std::set<std::pair<GridPoint, GridPoint>> diagonals;
    for (std::size_t k = 0; k < m.triangle_count(); ++k)
        for (int e = 0; e < 3; ++e) {
            GridPoint a = grid_of(m, m.indices[3 * k + std::size_t(e)], 10), b = grid_of(m, m.indices[3 * k + std::size_t(e + 1) % 3], 10);
            if (a.row != b.row && a.col != b.col) diagonals.insert(std::minmax(a, b));
        }
    EXPECT_EQ(diagonals.size(), 256u);
    for (int i = 0; i < 16; ++i)
        for (int j = 0; j < 16; ++j) {
            const bool main = (i + j) % 2 == 0;
            const std::pair<GridPoint, GridPoint> d =
                main ? std::minmax(GridPoint{i, j}, GridPoint{i + 1, j + 1}) : std::minmax(GridPoint{i, j + 1}, GridPoint{i + 1, j});
            EXPECT_TRUE(diagonals.count(d)) << "cell " << i << "," << j;
        }
    // Vertex attributes come from the terrain.
    for (std::size_t v = 0; v < m.positions.size(); ++v) {
        const GridPoint g = grid_of(m, std::uint32_t(v), 10);
        EXPECT_FLOAT_EQ(m.positions[v].y, t.sample_height(g.row, g.col));
        EXPECT_EQ(m.colors[v], t.color(g.row, g.col));
        // Normals are stored with 16-bit x and z: within 1e-3 rad of the terrain's.
        EXPECT_GT(glm::dot(m.normals[v], t.sample_normal(g.row, g.col)), std::cos(1e-3));
    }
    expect_conforming(m, 10, 17, 17);
}

TEST(RoamMesh, ConformingAndWithinBudget) {
    const Terrain t = rough(129, 129);
    RoamMesh roam(t);
    MeshArrays m;
    for (double heading : {0.0, 35.0, 200.0}) {
        const Camera cam = camera_at(640, 600, 900, heading);
        for (int budget : {2, 3, 10, 57, 256, 1000, 2047}) {
            const RoamStats s = roam.tessellate(cam, budget);
            roam.write_mesh(m);
            EXPECT_EQ(m.triangle_count(), s.triangles);
            EXPECT_LE(int(s.triangles), budget) << heading << " " << budget;
            EXPECT_GE(int(s.triangles), budget - 2) << heading << " " << budget;
            expect_conforming(m, 10, 129, 129);
        }
    }
}

// Priorities are nested (a child's error never exceeds its parent's), so the
// largest error can only fall as the budget grows. The buckets order errors to
// within one bucket (a factor 1 + 1/128), which bounds any rise.
TEST(RoamMesh, MaxErrorNeverRisesWithBudget) {
    const Terrain t = rough(129, 129);
    RoamMesh roam(t);
    for (bool with_focus : {false, true}) {
        const Camera cam = camera_at(640, 200, 900, 20);
        std::optional<glm::dvec2> focus;
        if (with_focus) focus = glm::dvec2(650, 260);
        double prev = 1e30;
        int falls = 0;
        for (int budget = with_focus ? 512 : 16; budget <= 20000; budget = budget * 5 / 4) {
            const RoamStats s = roam.tessellate(cam, budget, focus);
            EXPECT_LE(s.max_error_px, prev * (1.0 + 1.0 / 128)) << "budget " << budget;
            falls += s.max_error_px < prev;
            prev = s.max_error_px;
        }
        EXPECT_GT(falls, 10); // the error does fall
    }
}

// Triangles outside the view wedge are split only when forced: no diamond
// made wholly of invisible triangles could be merged back (its four children
// are leaves), so the out-of-view part is the coarsest the forced splits allow.
TEST(RoamMesh, OutsideTheWedgeStaysCoarsest) {
    const Terrain t = rough(129, 129);
    RoamMesh roam(t);
    for (double heading : {0.0, 100.0, 225.0}) {
        const RoamStats s = roam.tessellate(camera_at(640, 640, 900, heading, 50), 3000);
        ASSERT_GE(int(s.triangles), 2998);
        const auto& nodes = roam.nodes();
        auto invisible = [&](std::int32_t i) { return (nodes[std::size_t(i)].flags() & RoamMesh::kInvisible) != 0; };
        auto split = [&](std::int32_t i) { return (nodes[std::size_t(i)].flags() & RoamMesh::kSplit) != 0; };
        auto split_into_leaves = [&](std::int32_t i) {
            return split(i) && !split(roam.child(std::size_t(i))) && !split(roam.child(std::size_t(i)) + 1);
        };
        int mergeable = 0, invisible_leaves = 0, visible_leaves = 0, invisible_splits = 0;
        for (std::size_t i = 0; i < nodes.size(); ++i) {
            const auto& n = nodes[i];
            if (n.unused()) continue;
            if (!split(std::int32_t(i))) {
                (invisible(std::int32_t(i)) ? invisible_leaves : visible_leaves) += 1;
                continue;
            }
            if (!invisible(std::int32_t(i))) continue;
            ++invisible_splits;
            if (!split_into_leaves(std::int32_t(i))) continue;
            const std::int32_t partner = n.nb[1];
            // The partner across the hypotenuse at the same level was split with it.
            if (partner < 0 || (invisible(partner) && split_into_leaves(partner))) ++mergeable;
        }
        EXPECT_EQ(mergeable, 0) << "heading " << heading;
        EXPECT_GT(invisible_splits, 0);         // forced splits do reach out of view
        EXPECT_GT(visible_leaves, 4 * invisible_leaves) << "heading " << heading;
    }
}

// The triangle under the vehicle gets the maximum priority: even with a tiny
// budget the leaves around the focus point are half cells.
TEST(RoamMesh, FocusReachesTheFinestLevel) {
    const Terrain t = rough(129, 129);
    RoamMesh roam(t);
    // Focus behind the camera, where nothing would otherwise be refined.
    const glm::dvec2 focus{333.0, 121.0};
    roam.tessellate(camera_at(640, 640, 900, 0), 200, focus);
    int focus_leaves = 0;
    for (std::size_t i = 0; i < roam.nodes().size(); ++i) {
        const auto& n = roam.nodes()[i];
        if ((n.flags() & RoamMesh::kSplit) || !(n.flags() & RoamMesh::kFocus)) continue;
        ++focus_leaves;
        EXPECT_EQ(n.level(), roam.variance().finest_level());
    }
    EXPECT_GE(focus_leaves, 1);
    // Without the focus the same area stays coarse.
    roam.tessellate(camera_at(640, 640, 900, 0), 200);
    int finest = 0;
    for (const auto& n : roam.nodes())
        finest += !(n.flags() & RoamMesh::kSplit) && n.level() == roam.variance().finest_level();
    EXPECT_EQ(finest, 0);
}

// The read access to the bintree: every split node's children are one level
// finer, halve its hypotenuse at the midpoint (child 0 = (m, apex, v0), child
// 1 = (m, v1, apex)) and are each split or a leaf of their own; every node but
// the two roots is the child of exactly one split node; the pool slots no
// split used (the ends of chunks) are marked unused.
TEST(RoamMesh, ChildrenHalveTheirParent) {
    const Terrain t = rough(65, 65);
    RoamMesh roam(t);
    roam.tessellate(camera_at(100, 100, 800, 45), 2000);
    const auto nodes = roam.nodes();
    const auto vertices = roam.vertices();
    std::vector<int> parents(nodes.size(), 0);
    int splits = 0;
    int unused = 0;
    for (std::size_t i = 0; i < nodes.size(); ++i) {
        unused += nodes[i].unused();
        if (!(nodes[i].flags() & RoamMesh::kSplit) || nodes[i].unused()) continue;
        ++splits;
        const std::int32_t c = roam.child(i);
        ASSERT_GE(c, 2);
        ASSERT_LT(std::size_t(c) + 1, nodes.size());
        const auto& n = nodes[i];
        const auto& c0 = nodes[std::size_t(c)];
        const auto& c1 = nodes[std::size_t(c) + 1];
        EXPECT_EQ(c0.level(), n.level() + 1);
        EXPECT_EQ(c1.level(), n.level() + 1);
        const auto& v0 = vertices[n.v[1]];
        const auto& v1 = vertices[n.v[2]];
        const auto& m = vertices[c0.v[0]];
        EXPECT_EQ(2 * m.row, v0.row + v1.row);
        EXPECT_EQ(2 * m.col, v0.col + v1.col);
        EXPECT_EQ(c0.v, (std::array<std::uint32_t, 3>{c0.v[0], n.v[0], n.v[1]}));
        EXPECT_EQ(c1.v, (std::array<std::uint32_t, 3>{c0.v[0], n.v[2], n.v[0]}));
        ++parents[std::size_t(c)];
        ++parents[std::size_t(c) + 1];
    }
    EXPECT_GT(splits, 900);
    EXPECT_EQ(parents[0] + parents[1], 0);
    for (std::size_t i = 2; i < nodes.size(); ++i) EXPECT_EQ(parents[i], nodes[i].unused() ? 0 : 1) << "node " << i;
    EXPECT_LT(unused, int(nodes.size()));
}

// The mesh as a set of triangles, each starting at its least vertex (winding
// kept): the order of the output arrays follows the path the splits took.
std::vector<std::array<glm::vec3, 3>> triangle_set(const MeshArrays& m) {
    auto less = [](const glm::vec3& a, const glm::vec3& b) {
        return std::tie(a.x, a.y, a.z) < std::tie(b.x, b.y, b.z);
    };
    std::vector<std::array<glm::vec3, 3>> set;
    for (std::size_t t = 0; t < m.triangle_count(); ++t) {
        std::array<glm::vec3, 3> p;
        for (std::size_t k = 0; k < 3; ++k) p[k] = m.positions[m.indices[3 * t + k]];
        std::rotate(p.begin(), std::min_element(p.begin(), p.end(), less), p.end());
        set.push_back(p);
    }
    std::sort(set.begin(), set.end(), [&](const auto& a, const auto& b) {
        return std::lexicographical_compare(a.begin(), a.end(), b.begin(), b.end(), less);
    });
    return set;
}

// The same camera and budget give the same mesh whatever came before: a
// fresh RoamMesh, one whose last frame was coarser (its order-free threshold
// holds) and one whose last frame was finer (the threshold does not hold and
// the frame is refined again in order).
TEST(RoamMesh, RepeatableAcrossFrames) {
    const Terrain t = rough(129, 129);
    const Camera cam = camera_at(100, 100, 800, 45), other = camera_at(900, 700, 600, 200);
    for (int budget : {300, 3000}) {
        RoamMesh fresh(t);
        MeshArrays reference;
        const RoamStats first = fresh.tessellate(cam, budget);
        fresh.write_mesh(reference);
        EXPECT_EQ(first.passes, 2); // no threshold yet: found by a pass in order first
        // The arrays too are the same for a fresh mesh, however its threads ran.
        RoamMesh twin(t);
        twin.tessellate(cam, budget);
        MeshArrays twin_mesh;
        twin.write_mesh(twin_mesh);
        EXPECT_EQ(twin_mesh.indices, reference.indices) << budget;
        EXPECT_EQ(twin_mesh.positions, reference.positions) << budget;
        const RoamStats again = fresh.tessellate(cam, budget);
        MeshArrays m;
        fresh.write_mesh(m);
        EXPECT_EQ(again.passes, 1);
        EXPECT_LT(again.ordered_splits, again.splits / 4) << budget;
        EXPECT_EQ(triangle_set(m), triangle_set(reference)) << budget;
        for (int before : {budget / 8, budget * 4}) {
            RoamMesh roam(t);
            roam.tessellate(other, before);
            roam.tessellate(cam, before);
            const RoamStats s = roam.tessellate(cam, budget);
            roam.write_mesh(m);
            EXPECT_EQ(s.passes, before > budget ? 2 : 1) << budget << " after " << before;
            EXPECT_EQ(s.triangles, first.triangles);
            EXPECT_EQ(triangle_set(m), triangle_set(reference)) << budget << " after " << before;
        }
    }
    // Siblings often share their parent's clamped error: where the budget
    // ends between two such triangles, only the key decides.
    // A coarser last frame leaves many buckets to the ordered part; a finer
    // one makes the frame refined again from the bucket the count reached.
    RoamMesh roam(t);
    MeshArrays after_coarser, after_finer;
    int differ = 0;
    for (int budget = 100; budget < 4000; budget += 13) {
        roam.tessellate(cam, budget / 3);
        roam.tessellate(cam, budget);
        roam.write_mesh(after_coarser);
        roam.tessellate(cam, budget * 2);
        roam.tessellate(cam, budget);
        roam.write_mesh(after_finer);
        differ += triangle_set(after_coarser) != triangle_set(after_finer);
    }
    EXPECT_EQ(differ, 0);
}

// A 40 x 50 terrain is padded to 65 x 65; no output triangle lies in the
// padding, and once the budget suffices, none crosses the terrain's edge.
TEST(RoamMesh, PaddedTerrainEndsAtItsEdge) {
    const Terrain t = rough(40, 50);
    RoamMesh roam(t);
    EXPECT_EQ(roam.grid().rows(), 65);
    MeshArrays m;
    for (int budget : {4, 100, 2000, 3000}) {
        const RoamStats s = roam.tessellate(camera_above(t), budget);
        roam.write_mesh(m);
        EXPECT_LE(int(s.triangles), budget);
        std::set<std::uint32_t> used(m.indices.begin(), m.indices.end());
        int in_padding = 0, beyond_edge = 0;
        for (std::size_t k = 0; k < m.triangle_count(); ++k) {
            float min_x = 1e9f, min_z = 1e9f, max_x = 0, max_z = 0;
            for (int e = 0; e < 3; ++e) {
                const glm::vec3& p = m.positions[m.indices[3 * k + std::size_t(e)]];
                min_x = std::min(min_x, p.x), max_x = std::max(max_x, p.x);
                min_z = std::min(min_z, p.z), max_z = std::max(max_z, p.z);
            }
            in_padding += min_x >= t.width() || min_z >= t.depth();
            beyond_edge += max_x > t.width() || max_z > t.depth();
        }
        EXPECT_EQ(in_padding, 0) << budget;
        if (budget >= 2000) {
            EXPECT_EQ(beyond_edge, 0) << budget;
            EXPECT_GE(int(s.triangles), budget - 2);
        }
        // Inside the terrain, attributes are the terrain's own.
        for (std::uint32_t v : used) {
            const GridPoint g = grid_of(m, v, 10);
            if (g.row < 40 && g.col < 50) {
                EXPECT_EQ(m.colors[v], t.color(g.row, g.col));
            }
        }
    }
    // Full budget: exactly the terrain's own cells.
    const RoamStats s = roam.tessellate(camera_above(t), 1 << 20);
    EXPECT_EQ(s.triangles, 2u * 39u * 49u);
}

TEST(RoamMesh, RejectsBadRequests) {
    const Terrain t = rough(17, 17);
    RoamMesh roam(t);
    EXPECT_THROW(roam.tessellate(camera_above(t), 1), Error);
    Camera bad = camera_above(t);
    bad.far = 0.5;
    EXPECT_THROW(roam.tessellate(bad, 100), Error);
}
