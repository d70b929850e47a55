// Reduced tile levels (lod/TileSet.h "Levels", lod/RottgerQuadtree.h
// "Reduced patches"): a reduced quadtree's d2 equals the full one's with the
// stored d2 and never falls below it with the roughness bound, the level chosen before loading is one at which the full tile would
// not have refined further, tiles at different levels stitch without cracks,
// a visible set larger than the memory bound streams within the frame to
// the same mesh, and reduced tiles keep Zamri's depth fidelity.
#include "lod/QuadtreeAccuracy.h"
#include "lod/TileSet.h"

#include "core/DemoIsland.h"
#include "TileSeams.h"

#include "TestCameras.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <set>
#include <tuple>

using namespace overflight;

namespace {

Terrain island(int size) {
    DemoOptions o;
    o.size = size;
    return make_demo_island(o).terrain;
}

// A loader that also gives reduced tiles the full tile's d2 (as a tile
// directory does from its _d2 files).
TileLoader loader_with_d2(const Terrain& t, TileGrid& g) {
    g.d2_min_resolution = 4.0;
    return [&t, g, base = terrain_tile_loader(t, g)](int r, int c, int level) {
        TileSamples s = base(r, c, level);
        if (level > 0) {
            const std::vector<float> full = rottger_d2(cut_tile(t, g, r, c, false).samples, 4.0);
            const int n = s.samples.rows();
            for (int i = 0; i < n; ++i)
                for (int j = 0; j < n; ++j)
                    s.d2.push_back(full[std::size_t(i << level) * std::size_t(g.tile_size) + std::size_t(j << level)]);
        }
        return s;
    };
}

int levels_used(const TileFrameStats& s) {
    int n = 0;
    for (const int k : s.per_level) n += k > 0;
    return n;
}

} // namespace

// Every node of a reduced quadtree has at least the d2 of the same node in
// the full tile's quadtree, so the reduced tile never stops where the full
// one would refine.
TEST(TileLevels, ReducedD2StaysConservative) {
    const Terrain t = island(257);
    TileGrid g = terrain_tile_grid(t, 65);
    add_tile_levels(t, g);
    const double C = 4.0;
    for (const auto& [r, c] : {std::pair{1, 1}, std::pair{2, 1}, std::pair{3, 2}}) {
        const TileSamples full = cut_tile(t, g, r, c, true);
        const RottgerQuadtree q(full.samples, full.normals, r * 64, c * 64, C);
        for (int m = 1; m <= g.coarsest_level(); ++m) {
            const TileSamples red = cut_tile(t, g, r, c, true, m);
            const double finer = propagated_d2_bound(g.roughness[g.index(r, c)], m - 1, C);
            const RottgerQuadtree rq(red.samples, red.normals, r * 64, c * 64, C, 1 << m, finer);
            const int n = red.samples.rows();
            for (int h = 1; 2 * h < n; h *= 2)
                for (int ci = h; ci < n; ci += 2 * h)
                    for (int cj = h; cj < n; cj += 2 * h) {
                        const float full_d2 = q.d2(ci << m, cj << m);
                        ASSERT_GE(rq.d2(ci, cj), full_d2 * (1 - 1e-5f)) << "level " << m << " node " << ci << "," << cj;
                    }
        }
    }
}

// With the full tile's d2 at its samples, every node of a reduced quadtree
// has exactly the full quadtree's d2: the reduced tile refines as the full
// one would.
TEST(TileLevels, ReducedD2FromTheFullTileIsExact) {
    const Terrain t = island(257);
    TileGrid g = terrain_tile_grid(t, 65);
    for (const auto& [r, c] : {std::pair{1, 1}, std::pair{2, 1}, std::pair{3, 2}}) {
        const TileSamples full = cut_tile(t, g, r, c, true);
        const RottgerQuadtree q(full.samples, full.normals, r * 64, c * 64, 4.0);
        const std::vector<float> d2 = rottger_d2(full.samples, 4.0);
        for (int m = 1; m <= g.coarsest_level(); ++m) {
            const TileSamples red = cut_tile(t, g, r, c, true, m);
            const int n = red.samples.rows();
            std::vector<float> finest;
            for (int i = 0; i < n; ++i)
                for (int j = 0; j < n; ++j) finest.push_back(d2[full.samples.index(i << m, j << m)]);
            const RottgerQuadtree rq(red.samples, red.normals, r * 64, c * 64, 4.0, 1 << m, 0.0, &finest);
            for (int h = 1; 2 * h < n; h *= 2)
                for (int ci = h; ci < n; ci += 2 * h)
                    for (int cj = h; cj < n; cj += 2 * h)
                        ASSERT_EQ(rq.d2(ci, cj), q.d2(ci << m, cj << m)) << "level " << m << " node " << ci << "," << cj;
        }
    }
}

// The level chosen before loading: the full tile's quadtree, refined for
// the same eye, subdivides no node of half-size 2^level.
TEST(TileLevels, ChosenLevelIsOneTheFullTileWouldNotRefine) {
    const Terrain t = island(1025);
    TileGrid g = terrain_tile_grid(t, 65);
    add_tile_levels(t, g);
    TileSet set(g, terrain_tile_loader(t, g), std::size_t(1) << 30);
    const Camera cam = test::camera_at({500, t.max_height() + 100, -100}, 20, -8, 40000, 640, 360);
    const double c = rottger_c(1.0, cam.focal_px(), 4.0);
    int reduced = 0;
    for (int r = 0; r < g.tile_rows; ++r)
        for (int col = 0; col < g.tile_cols; ++col) {
            const int level = set.needed_level(r, col, cam.eye, c);
            if (level == 0) continue;
            ++reduced;
            const TileSamples full = cut_tile(t, g, r, col, true);
            RottgerQuadtree q(full.samples, full.normals, r * 64, col * 64, 4.0);
            q.refine(cam.eye, c);
            const int h = 1 << level;
            for (int ci = h; ci < 65; ci += 2 * h)
                for (int cj = h; cj < 65; cj += 2 * h)
                    ASSERT_FALSE(q.subdivided(ci, cj)) << "tile " << r << "," << col << " level " << level;
        }
    EXPECT_GT(reduced, 50);
}

// Tiles at different levels share their seams: every inner edge is used by
// two triangles, over several views and error targets.
TEST(TileLevels, NoCrackBetweenLevels) {
    const Terrain t = island(1025);
    TileGrid g = terrain_tile_grid(t, 65);
    add_tile_levels(t, g);
    TileGrid gd = g;
    TileSet bounded(g, terrain_tile_loader(t, g), std::size_t(1) << 30);
    const TileLoader exact_loader = loader_with_d2(t, gd);
    TileSet exact(gd, exact_loader, std::size_t(1) << 30);
    const float W = t.width();
    const std::tuple<glm::dvec3, double, double> views[] = {
        {glm::dvec3(500, t.max_height() + 100, -100), 20.0, -8.0},
        {glm::dvec3(W / 2, t.max_height() + 30, W / 2), 135.0, -5.0},
        {glm::dvec3(W / 3, 3000, W / 3), 60.0, -35.0}};
    for (TileSet* set : {&bounded, &exact})
        for (const auto& [eye, heading, pitch] : views)
            for (const double err : {0.5, 1.0, 4.0}) {
                MeshArrays m;
                const TileFrameStats s = set->build_mesh(test::camera_at(eye, heading, pitch, 40000, 640, 360), err, m);
                EXPECT_GE(levels_used(s), 2) << "error " << err << " view " << heading;
                EXPECT_EQ(test::open_edges(m, set->visible_tiles(), float(g.tile_world_size())), 0) << "error " << err;
            }
}

// A bound below one frame's visible set: the frame is built row by row and
// drawn tiles are evicted, the cache stays under the bound, and the mesh is
// the one an unbounded cache builds.
TEST(TileLevels, StreamsWithinTheFrameUnderTheBound) {
    const Terrain t = island(1025);
    TileGrid g = terrain_tile_grid(t, 65);
    add_tile_levels(t, g);
    const Camera cam = test::camera_at({t.width() / 2, t.max_height() + 50, t.width() / 2}, 30, -10, 40000, 640, 360);
    TileSet unbounded(g, terrain_tile_loader(t, g), std::size_t(1) << 30);
    MeshArrays ref;
    const TileFrameStats all = unbounded.build_mesh(cam, 1.0, ref);
    EXPECT_EQ(all.streamed, 0);
    const std::size_t bound = all.cache_bytes / 2;
    TileSet set(g, terrain_tile_loader(t, g), bound);
    MeshArrays m;
    const TileFrameStats s = set.build_mesh(cam, 1.0, m);
    EXPECT_GT(s.streamed, 0);
    EXPECT_LE(s.cache_bytes, bound);
    EXPECT_EQ(s.triangles, all.triangles);
    EXPECT_EQ(m.positions, ref.positions);
    EXPECT_EQ(m.indices, ref.indices);
    EXPECT_EQ(test::open_edges(m, set.visible_tiles(), float(g.tile_world_size())), 0);
    // The next frame streams again and gives the same mesh.
    const TileFrameStats s2 = set.build_mesh(cam, 1.0, m);
    EXPECT_GT(s2.streamed, 0);
    EXPECT_EQ(s2.triangles, all.triangles);
}

// Zamri's fidelity with reduced far tiles (2049^2 island, 1280x720, 1 px,
// far 20 km): depth within 3 % of the full mesh on >= 95 % of terrain
// pixels and the largest sample error near 1 px, as with full tiles, with
// about the same triangles and less tile memory.
TEST(TileLevels, AccuracyAgainstFullResolution) {
    const Terrain t = island(2049);
    TileGrid g = terrain_tile_grid(t, 257);
    TileSet full_tiles(g, terrain_tile_loader(t, g), std::size_t(1) << 30);
    add_tile_levels(t, g);
    const TileLoader loader = loader_with_d2(t, g);
    TileSet reduced(g, loader, std::size_t(1) << 30);
    Camera cam = test::camera_at({t.width() / 2, t.max_height() + 150, -300}, 0, -12, 20000, 640, 360);
    cam.width = 1280;
    cam.height = 720;
    MeshArrays m, mf;
    const TileFrameStats s = reduced.build_mesh(cam, 1.0, m);
    const TileFrameStats sf = full_tiles.build_mesh(cam, 1.0, mf);
    const DepthImage ref = rasterize_depth(full_resolution_mesh(t), cam);
    const DepthAgreement a = compare_depth(rasterize_depth(m, cam), ref, cam, 0.03);
    const ScreenError e = screen_space_error(m, t, cam);
    std::printf("reduced tiles: %zu triangles (full tiles %zu), cache %.1f MiB (full tiles %.1f), depth within 3%%: "
                "%.2f %%, screen error max %.2f px\n",
                s.triangles, sf.triangles, double(s.cache_bytes) / 1048576.0, double(sf.cache_bytes) / 1048576.0,
                100 * a.share(), e.max_px);
    EXPECT_GE(levels_used(s), 3);
    EXPECT_GE(a.share(), 0.95);
    EXPECT_LE(e.max_px, 1.25);
    EXPECT_LT(double(s.cache_bytes), 0.8 * double(sf.cache_bytes));
    EXPECT_GT(double(s.triangles), 0.9 * double(sf.triangles));
}
