// Röttger's quadtree: d2 values on literal height fields (worked by hand in
// the comments), the subdivision extremes, and the no-crack property inside a
// patch and across patch seams.
#include "lod/RottgerQuadtree.h"

#include "core/Error.h"

#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include <cmath>
#include <map>
#include <memory>
#include <set>
#include <tuple>
#include <vector>

using namespace overflight;

namespace {

Terrain field(int n, const std::vector<int>& raw, float hs = 1.0f) {
    Terrain t(n, n, hs);
    for (std::size_t i = 0; i < raw.size(); ++i) t.heights()[i] = std::uint16_t(raw[i]);
    return t;
}

std::vector<glm::vec3> normals_of(const Terrain& t) {
    std::vector<glm::vec3> n;
    for (int i = 0; i < t.rows(); ++i)
        for (int j = 0; j < t.cols(); ++j) n.push_back(t.sample_normal(i, j));
    return n;
}

// Checks that a triangle mesh over the rectangle [0, W] x [0, D] (XZ) is
// conforming: every triangle counter-clockwise seen from above, every
// undirected edge used by exactly two triangles (once in each direction)
// unless it lies on the rectangle's border, where it is used once, and the
// triangles' XZ areas add up to the rectangle (so there is no hole and no
// overlap). A T-junction or a crack leaves an inner edge used once.
void expect_conforming(const MeshArrays& m, float W, float D) {
    using Key = std::tuple<float, float, float, float>;
    std::map<Key, int> directed;
    double area = 0;
    for (std::size_t t = 0; t < m.indices.size(); t += 3) {
        const glm::vec3 a = m.positions[m.indices[t]], b = m.positions[m.indices[t + 1]],
                        c = m.positions[m.indices[t + 2]];
        const double cross_y = double(b.z - a.z) * (c.x - a.x) - double(b.x - a.x) * (c.z - a.z);
        ASSERT_GT(cross_y, 0) << "triangle " << t / 3 << " is not counter-clockwise from above";
        area += 0.5 * cross_y;
        const glm::vec3 v[3] = {a, b, c};
        for (int e = 0; e < 3; ++e) {
            const glm::vec3 p = v[e], q = v[(e + 1) % 3];
            const int uses = ++directed[Key{p.x, p.z, q.x, q.z}];
            ASSERT_EQ(uses, 1) << "directed edge used twice";
        }
    }
    EXPECT_NEAR(area, double(W) * D, 1e-3 * W * D);
    for (const auto& [k, count] : directed) {
        const auto [px, pz, qx, qz] = k;
        if (directed.count(Key{qx, qz, px, pz})) continue;
        const bool border = (px == qx && (px == 0 || px == W)) || (pz == qz && (pz == 0 || pz == D));
        ASSERT_TRUE(border) << "edge (" << px << "," << pz << ")-(" << qx << "," << qz
                            << ") is used by one triangle but is not on the border: crack";
    }
}

std::vector<int> random_field(int n, unsigned seed, int amplitude) {
    std::vector<int> v(std::size_t(n) * n);
    unsigned s = seed;
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) {
            s = s * 1664525u + 1013904223u;
            // Smooth slope plus noise that is rougher in the east half.
            const int noise = int((s >> 16) % unsigned(j > n / 2 ? amplitude : amplitude / 8 + 1));
            v[std::size_t(i) * n + j] = 1000 + 3 * i + 2 * j + noise;
        }
    return v;
}

} // namespace

// 5x5, hs = vs = 1, a bump of 4 at (1,1) and 8 at the SE corner:
//   0 0 0 0 0
//   0 4 0 0 0
//   0 0 0 0 0
//   0 0 0 0 0
//   0 0 0 0 8
// Node (1,1), h=1, d=2: everything 0 but the centre; centre vs both diagonals
//   |4 - 0| = 4 -> d2 = 4/2 = 2.
// Node (3,3), h=1, d=2: SE corner (4,4)=8. Midpoint (4,3): |0 - (0+8)/2| = 4,
//   (3,4): 4, centre vs NW-SE diagonal |0 - (0+8)/2| = 4 -> d2 = 4/2 = 2.
// Nodes (1,3), (3,1): all zero -> 0.
// Root (2,2), h=2, d=4: (4,2) vs (0+8)/2 -> 4, (2,4) -> 4, centre vs NW-SE
//   -> 4: own d2 = 4/4 = 1. Propagated with K = C/(2(C-1)):
//   C = 2: K = 1,   max(1, 1 * 2)   = 2;
//   C = 3: K = 3/4, max(1, 0.75 * 2) = 1.5.
TEST(RottgerQuadtree, D2On5x5ByHand) {
    const Terrain t = field(5, {0, 0, 0, 0, 0, 0, 4, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 8});
    const auto n = normals_of(t);
    RottgerQuadtree q2(t, n, 0, 0, 2.0);
    EXPECT_FLOAT_EQ(q2.d2(1, 1), 2.0f);
    EXPECT_FLOAT_EQ(q2.d2(3, 3), 2.0f);
    EXPECT_FLOAT_EQ(q2.d2(1, 3), 0.0f);
    EXPECT_FLOAT_EQ(q2.d2(3, 1), 0.0f);
    EXPECT_FLOAT_EQ(q2.d2(2, 2), 2.0f);
    RottgerQuadtree q3(t, n, 0, 0, 3.0);
    EXPECT_FLOAT_EQ(q3.d2(2, 2), 1.5f);
    // Horizontal scale 2 doubles every d: all d2 halve.
    const Terrain t2 = field(5, std::vector<int>(t.heights().begin(), t.heights().end()), 2.0f);
    RottgerQuadtree h2(t2, n, 0, 0, 3.0);
    EXPECT_FLOAT_EQ(h2.d2(1, 1), 1.0f);
    EXPECT_FLOAT_EQ(h2.d2(2, 2), 0.75f);
}

// 9x9, hs = vs = 1, all zero except (1,1) = 8, (2,2) = 4, (0,8) = 16.
// Level 1 (h=1, d=2):
//   (1,1): centre 8 vs NE-SW (0+0)/2 -> 8 (vs NW-SE (0+4)/2 -> 6)  -> d2 = 4
//   (1,3): corner (2,2)=4: midpoints (2,3), (1,2) -> 2; centre vs NE-SW -> 2 -> 1
//   (3,1), (3,3): the same by symmetry -> 1
//   (1,7): corner (0,8)=16: midpoints (0,7), (1,8) -> 8; centre vs NE-SW -> 8 -> 4
// Level 2 (h=2, d=4):
//   (2,2): corners and midpoints 0, centre 4 -> own 4/4 = 1; children 4,1,1,1
//   (2,6): corner (0,8)=16: (0,6), (2,8), centre vs NE-SW -> 8 -> own 2; child (1,7) = 4
// Root (4,4), h=4, d=8: (0,4), (4,8), centre vs NE-SW -> 8 -> own 1.
// C = 2 (K = 1):   (2,2) = 4, (2,6) = 4, root = 4.
// C = 4 (K = 2/3): (2,2) = max(1, 8/3) = 8/3, (2,6) = max(2, 8/3) = 8/3,
//                  root = max(1, 2/3 * 8/3) = 16/9.
TEST(RottgerQuadtree, D2On9x9ByHand) {
    std::vector<int> raw(81, 0);
    raw[1 * 9 + 1] = 8;
    raw[2 * 9 + 2] = 4;
    raw[0 * 9 + 8] = 16;
    const Terrain t = field(9, raw);
    const auto n = normals_of(t);
    RottgerQuadtree q(t, n, 0, 0, 2.0);
    EXPECT_FLOAT_EQ(q.d2(1, 1), 4.0f);
    EXPECT_FLOAT_EQ(q.d2(1, 3), 1.0f);
    EXPECT_FLOAT_EQ(q.d2(3, 1), 1.0f);
    EXPECT_FLOAT_EQ(q.d2(3, 3), 1.0f);
    EXPECT_FLOAT_EQ(q.d2(1, 5), 0.0f);
    EXPECT_FLOAT_EQ(q.d2(1, 7), 4.0f);
    EXPECT_FLOAT_EQ(q.d2(2, 2), 4.0f);
    EXPECT_FLOAT_EQ(q.d2(2, 6), 4.0f);
    EXPECT_FLOAT_EQ(q.d2(6, 2), 0.0f);
    EXPECT_FLOAT_EQ(q.d2(4, 4), 4.0f);
    RottgerQuadtree q4(t, n, 0, 0, 4.0);
    EXPECT_FLOAT_EQ(q4.d2(2, 2), 8.0f / 3.0f);
    EXPECT_FLOAT_EQ(q4.d2(2, 6), 8.0f / 3.0f);
    EXPECT_FLOAT_EQ(q4.d2(4, 4), 16.0f / 9.0f);
}

// The propagation makes d2 monotone: a parent's d2 is at least K times each child's.
TEST(RottgerQuadtree, D2IsMonotoneOnRandomField) {
    const Terrain t = field(33, random_field(33, 7, 400));
    const auto n = normals_of(t);
    const double C = 2.5, K = C / (2 * (C - 1));
    RottgerQuadtree q(t, n, 0, 0, C);
    for (int h = 2; h <= 16; h *= 2)
        for (int ci = h; ci < 33; ci += 2 * h)
            for (int cj = h; cj < 33; cj += 2 * h)
                for (int di : {-1, 1})
                    for (int dj : {-1, 1})
                        EXPECT_GE(q.d2(ci, cj) * (1 + 1e-6), K * q.d2(ci + di * h / 2, cj + dj * h / 2));
}

TEST(RottgerQuadtree, ExtremesAreRootAndFullResolution) {
    const Terrain t = field(17, random_field(17, 3, 300));
    const auto n = normals_of(t);
    RottgerQuadtree q(t, n, 0, 0, 2.0);
    MeshArrays m;
    // Far above: the root alone. With no neighbour patch its border edges
    // keep their midpoints, so the fan has 8 triangles over 9 vertices.
    q.refine({8, 1e7, 8}, 1.0);
    EXPECT_EQ(q.append_fans(m), 8u);
    EXPECT_EQ(m.positions.size(), 9u);
    expect_conforming(m, 16, 16);
    m.clear();
    q.refine({8, 1100, 8}, 1e9); // tiny error target: everything
    EXPECT_EQ(q.append_fans(m), 2u * 16 * 16);
    EXPECT_EQ(m.positions.size(), 17u * 17);
    expect_conforming(m, 16, 16);
    // World positions follow DESIGN sec. 1 and normals/colors ride along.
    ASSERT_EQ(m.normals.size(), m.positions.size());
    ASSERT_EQ(m.colors.size(), m.positions.size());
    for (const glm::vec3& p : m.positions) {
        const int j = int(p.x), i = int(p.z);
        EXPECT_EQ(p.y, t.sample_height(i, j));
    }
}

TEST(RottgerQuadtree, NoCrackInsideOnePatch) {
    const Terrain t = field(65, random_field(65, 11, 2000));
    const auto n = normals_of(t);
    for (double C : {1.2, 2.0, 4.0}) {
        RottgerQuadtree q(t, n, 0, 0, C);
        for (const glm::dvec3 eye : {glm::dvec3(3, 2500, 5), glm::dvec3(60, 2600, 20), glm::dvec3(-30, 3500, 90)}) {
            MeshArrays m;
            q.refine(eye, 0.3);
            q.append_fans(m);
            EXPECT_GT(m.triangle_count(), 4u);
            EXPECT_LT(m.triangle_count(), 2u * 64 * 64);
            expect_conforming(m, 64, 64);
        }
    }
}

// A 2x2 grid of 33x33 patches cut from one 65x65 field (they share their
// edge samples). Each patch refines on its own (different roughness, so the
// levels differ at the seams); with neighbours set, the union is conforming.
TEST(RottgerQuadtree, NoCrackAcrossPatchSeams) {
    const Terrain whole = field(65, random_field(65, 5, 3000));
    std::vector<Terrain> patches;
    std::vector<std::vector<glm::vec3>> normals;
    for (int tr = 0; tr < 2; ++tr)
        for (int tc = 0; tc < 2; ++tc) {
            Terrain p(33, 33, 1.0f);
            for (int i = 0; i < 33; ++i)
                for (int j = 0; j < 33; ++j) p.raw(i, j) = whole.raw(tr * 32 + i, tc * 32 + j);
            normals.push_back(normals_of(p));
            patches.push_back(std::move(p));
        }
    for (double C : {1.5, 2.0, 3.0}) {
        std::vector<std::unique_ptr<RottgerQuadtree>> q;
        for (int k = 0; k < 4; ++k)
            q.push_back(std::make_unique<RottgerQuadtree>(patches[std::size_t(k)], normals[std::size_t(k)], (k / 2) * 32,
                                                          (k % 2) * 32, C));
        q[0]->set_neighbour(RottgerQuadtree::East, q[1].get());
        q[0]->set_neighbour(RottgerQuadtree::South, q[2].get());
        q[1]->set_neighbour(RottgerQuadtree::West, q[0].get());
        q[1]->set_neighbour(RottgerQuadtree::South, q[3].get());
        q[2]->set_neighbour(RottgerQuadtree::North, q[0].get());
        q[2]->set_neighbour(RottgerQuadtree::East, q[3].get());
        q[3]->set_neighbour(RottgerQuadtree::North, q[1].get());
        q[3]->set_neighbour(RottgerQuadtree::West, q[2].get());
        for (const glm::dvec3 eye : {glm::dvec3(31, 3500, 33), glm::dvec3(2, 3300, 60), glm::dvec3(70, 3600, -10)}) {
            MeshArrays m;
            for (auto& p : q) p->refine(eye, 0.3);
            for (auto& p : q) p->append_fans(m);
            expect_conforming(m, 64, 64);
        }
        // Without the neighbour links the seams would crack: the check can fail.
        for (auto& p : q)
            for (auto s : {RottgerQuadtree::North, RottgerQuadtree::South, RottgerQuadtree::West, RottgerQuadtree::East})
                p->set_neighbour(s, nullptr);
        MeshArrays m;
        for (auto& p : q) p->refine({31, 3500, 33}, 0.3);
        for (auto& p : q) p->append_fans(m);
        std::map<std::tuple<float, float, float, float>, int> directed;
        for (std::size_t t = 0; t < m.indices.size(); t += 3)
            for (int e = 0; e < 3; ++e) {
                const glm::vec3 a = m.positions[m.indices[t + e]], b = m.positions[m.indices[t + (e + 1) % 3]];
                directed[{a.x, a.z, b.x, b.z}]++;
            }
        int unmatched_inner = 0;
        for (const auto& [k, c] : directed) {
            const auto [px, pz, qx, qz] = k;
            const bool border = (px == qx && (px == 0 || px == 64)) || (pz == qz && (pz == 0 || pz == 64));
            if (!directed.count({qx, qz, px, pz}) && !border) ++unmatched_inner;
        }
        EXPECT_GT(unmatched_inner, 0);
    }
}

// With a frustum, nodes whose box lies wholly outside it stay whole (Zamri's
// culling carried down to nodes): here the frustum is the slab 0 <= X <= 16
// of a 65x65 patch and the error target asks for everything, so the slab is
// at full resolution, nothing east of it is subdivided, and the mesh is
// still conforming.
TEST(RottgerQuadtree, NodesOutsideTheFrustumStayCoarse) {
    const Terrain t = field(65, random_field(65, 13, 500));
    const auto n = normals_of(t);
    RottgerQuadtree q(t, n, 0, 0, 2.0);
    Frustum slab;
    slab.planes = {Plane{{1, 0, 0}, 0.0},     Plane{{-1, 0, 0}, 16.0}, Plane{{0, 1, 0}, 1e6},
                   Plane{{0, -1, 0}, 1e6},    Plane{{0, 0, 1}, 1e6},   Plane{{0, 0, -1}, 1e6}};
    q.refine({8, 3000, 32}, 1e9, &slab);
    MeshArrays m;
    q.append_fans(m);
    expect_conforming(m, 64, 64);
    std::set<std::pair<float, float>> vertices;
    for (const glm::vec3& p : m.positions) vertices.insert({p.x, p.z});
    for (int i = 0; i <= 64; ++i)
        for (int j = 0; j <= 16; ++j) EXPECT_TRUE(vertices.count({float(j), float(i)})) << i << "," << j;
    for (int h = 2; h <= 32; h *= 2)
        for (int ci = h; ci < 65; ci += 2 * h)
            for (int cj = h; cj < 65; cj += 2 * h)
                if (cj - h > 16) {
                    EXPECT_FALSE(q.subdivided(ci, cj)) << "node " << ci << "," << cj << " h " << h;
                }
    EXPECT_LT(m.triangle_count(), 2u * 64 * 64 / 3);
    // Without the frustum the same target refines everything.
    MeshArrays all;
    q.refine({8, 3000, 32}, 1e9);
    EXPECT_EQ(q.append_fans(all), 2u * 64 * 64);
}

TEST(RottgerQuadtree, RejectsBadPatch) {
    Terrain t(6, 6, 1.0f);
    std::vector<glm::vec3> n(36);
    EXPECT_THROW(RottgerQuadtree(t, n, 0, 0), Error);
    Terrain ok(5, 5, 1.0f);
    EXPECT_THROW(RottgerQuadtree(ok, n, 0, 0), Error);
    std::vector<glm::vec3> n25(25);
    EXPECT_THROW(RottgerQuadtree(ok, n25, 0, 0, 1.0), Error);
    EXPECT_THROW(rottger_c(0.0, 100.0, 2.0), Error);
    EXPECT_DOUBLE_EQ(rottger_c(2.0, 1000.0, 2.5), 200.0);
}
