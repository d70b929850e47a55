// The quadtree over a tile directory streams its imagery tiles with the
// heights (lod/TileSet.h set_imagery, gl/TiledImageryTexture.h): Olinda
// tiled with its 28.5 m Landsat scene, seen close by the quadtree, shows the
// imagery's detail (high-frequency energy, as tests/gl/imagery_test.cpp
// measures it, at least twice that of the same tiles without imagery), no
// black pixel, and the colors of the in-memory imagery's mesh render.
#include "ImageMeasures.h"
#include "TestCameras.h"
#include "TestSupport.h"
#include "gl/HeadlessRenderer.h"
#include "io/ImageWriters.h"
#include "io/LoadTerrain.h"
#include "io/TileDirectory.h"
#include "io/WindowedTiler.h"
#include "lod/TileSet.h"
#include "methods/MethodTable.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>

using namespace overflight;
using test::black_pixels;
using test::laplacian_energy;
using test::mean_difference;

namespace {

struct Frame {
    ColorImage color;
    DepthImage depth;
    std::optional<TileFrameStats> tiles;
};

Frame render(const DataSet& d, gl::HeadlessRenderer& r, const char* method, const Camera& cam, const std::string& dir) {
    MethodSettings settings;
    settings.tile_size = 33;
    MethodContext context{d.terrain, settings, {}};
    if (!dir.empty())
        context.tiles = [dir, bound = settings.cache_bytes] {
            const TileIndex ix = read_tile_index(dir);
            auto tiles = std::make_unique<TileSet>(ix.grid, tile_directory_loader(dir, ix), bound);
            if (ix.imagery.present()) tiles->set_imagery(ix.imagery, tile_directory_imagery_loader(dir, ix), bound);
            return tiles;
        };
    const std::unique_ptr<TerrainMethod> m = find_terrain_method(method)->create(context);
    MethodStats stats;
    Frame f;
    Environment env = d.environment;
    env.fog_density = 0;
    r.render(m->produce({cam, env, std::nullopt}, stats), cam, env, {}, f.color, &f.depth);
    f.tiles = stats.tiles;
    return f;
}


long long terrain_pixels(const Frame& f) {
    long long n = 0;
    for (const float d : f.depth.pixels) n += d < 1.0f;
    return n;
}

} // namespace

TEST(ImageryTiles, QuadtreeOverTiledOlindaShowsTheLandsatDetail) {
    OVERFLIGHT_SHARED_FILE(dem, "paired/olinda/olinda_dem_utm25s.tif");
    OVERFLIGHT_SHARED_FILE(landsat, "paired/olinda/L7_ETMs.tif");
    test::ScratchDir scratch;
    const std::string with = scratch / "with", without = scratch / "without";
    for (const std::string& dir : {with, without}) {
        WindowedTileOptions w;
        w.tile.tile_size = 33;
        w.tile.measures = rottger_tile_measures();
        if (dir == with) w.color_path = landsat;
        tile_raster_in_windows(dem, dir, w);
    }
    const DataSet tiled = load_tile_directory(with), plain = load_tile_directory(without);
    LoadOptions lo;
    lo.color_path = landsat;
    const DataSet whole = load_terrain(dem, lo);
    // 600 m above the ground in the south of Olinda, looking north and down (imagery_test.cpp's view).
    const Terrain& t = whole.terrain;
    const double x = 0.5 * t.width(), z = 0.75 * t.depth();
    const Camera cam =
        test::camera_at({x, t.height_bilinear(float(x), float(z)) + 600.0, z}, 180.0, -25.0, 1.5 * t.width(), 480, 300);
    // One renderer (and GL context) at a time.
    const auto frame = [&](const DataSet& d, const char* method, const std::string& dir) {
        gl::HeadlessRenderer r(d.terrain, Scene{});
        return render(d, r, method, cam, dir);
    };
    const Frame fine = frame(tiled, "quadtree", with);
    const Frame coarse = frame(plain, "quadtree", without);
    const Frame mesh = frame(whole, "mesh", "");
    const char* out = std::getenv("OVERFLIGHT_TEST_PNG_DIR");
    if (out) {
        write_png(std::string(out) + "/quadtree_imagery_tiles.png", fine.color);
        write_png(std::string(out) + "/quadtree_without_imagery.png", coarse.color);
        write_png(std::string(out) + "/mesh_in_memory_imagery.png", mesh.color);
    }
    ASSERT_TRUE(fine.tiles.has_value());
    const double e = laplacian_energy(fine), e0 = laplacian_energy(coarse);
    const double diff = mean_difference(fine, mesh);
    std::printf("  imagery tiles shown: %d of %d visible (%d loaded)\n", fine.tiles->imagery_tiles, fine.tiles->visible,
                fine.tiles->imagery_loaded);
    std::printf("  high-frequency energy: quadtree with imagery tiles %.1f / without %.1f = %.2fx\n", e, e0, e / e0);
    std::printf("  mean color difference to the in-memory imagery's mesh: %.2f\n", diff);
    std::fflush(stdout);
    EXPECT_GT(fine.tiles->imagery_tiles, 0);
    EXPECT_GT(terrain_pixels(fine), 480 * 300 / 2);
    EXPECT_GE(e, 2.0 * e0);
    EXPECT_EQ(black_pixels(fine), 0);
    // The same texels, trilinear and anisotropic both; the quadtree's
    // simplified surface moves and lights some pixels differently.
    EXPECT_LT(diff, 8.0);
}
