// Imagery at its own resolution (core/ImageryPyramid.h) in the ray caster
// and the mesh: on Olinda (a 28.5 m Landsat scene over a 90 m DEM) a close
// view shows the imagery's detail, measured as the mean squared Laplacian of
// the luminance on terrain pixels, at least twice that of the same view with
// one color per DEM sample, in `voxel` and in `mesh`; voxel and mesh agree on
// the imagery's colors; a color raster that covers only part of the DEM
// leaves no black pixel (the elevation ramp + hillshade shows through).
#include "ImageMeasures.h"
#include "TestCameras.h"
#include "TestSupport.h"
#include "core/ImageryPyramid.h"
#include "gl/HeadlessRenderer.h"
#include "io/LoadTerrain.h"
#include "io/RasterFile.h"
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
};

Frame render(const DataSet& d, gl::HeadlessRenderer& r, const char* method, const Camera& cam) {
    const MethodSettings settings;
    const std::unique_ptr<TerrainMethod> m = find_terrain_method(method)->create({d.terrain, settings, {}});
    MethodStats stats;
    Frame f;
    Environment env = d.environment;
    env.fog_density = 0;
    r.render(m->produce({cam, env, std::nullopt}, stats), cam, env, {}, f.color, &f.depth);
    return f;
}


// 600 m above the ground in the south of Olinda, looking north and down.
Camera close_view(const Terrain& t) {
    const double x = 0.5 * t.width(), z = 0.75 * t.depth();
    return test::camera_at({x, t.height_bilinear(float(x), float(z)) + 600.0, z}, 180.0, -25.0, 1.5 * t.width(), 480,
                           300);
}

} // namespace

TEST(Imagery, OlindaCloseViewShowsTheLandsatDetailInVoxelAndMesh) {
    OVERFLIGHT_SHARED_FILE(dem, "paired/olinda/olinda_dem_utm25s.tif");
    OVERFLIGHT_SHARED_FILE(landsat, "paired/olinda/L7_ETMs.tif");
    LoadOptions options;
    options.color_path = landsat;
    const DataSet fine = load_terrain(dem, options);
    ASSERT_NE(fine.terrain.imagery(), nullptr);
    // About 28.5 m per texel over the 90 m cells, the DEM fully covered.
    EXPECT_NEAR(fine.terrain.imagery()->texel_size(0), 28.5, 0.5);
    EXPECT_GT(fine.terrain.imagery()->coverage(), 0.99);
    DataSet coarse = fine; // one color per sample: the imagery averaged onto the DEM grid
    coarse.terrain.set_imagery(nullptr);
    const Camera cam = close_view(fine.terrain);
    gl::HeadlessRenderer rf(fine.terrain, Scene{});
    gl::HeadlessRenderer rc(coarse.terrain, Scene{});
    const Frame voxel = render(fine, rf, "voxel", cam), voxel_dem = render(coarse, rc, "voxel", cam);
    const Frame mesh = render(fine, rf, "mesh", cam), mesh_dem = render(coarse, rc, "mesh", cam);
    const double ev = laplacian_energy(voxel), ev0 = laplacian_energy(voxel_dem);
    const double em = laplacian_energy(mesh), em0 = laplacian_energy(mesh_dem);
    const double diff = mean_difference(voxel, mesh), diff0 = mean_difference(voxel_dem, mesh_dem);
    std::printf("  high-frequency energy: voxel %.1f / %.1f = %.2fx, mesh %.1f / %.1f = %.2fx\n", ev, ev0, ev / ev0, em,
                em0, em / em0);
    std::printf("  voxel vs mesh mean color difference: %.2f with imagery, %.2f at DEM resolution\n", diff, diff0);
    EXPECT_GE(ev, 2.0 * ev0);
    EXPECT_GE(em, 2.0 * em0);
    // Nearest texel on the ray caster's level against the mesh's trilinear,
    // anisotropic filtering; the lighting differs as without imagery.
    EXPECT_LT(diff, 8.0);
}

TEST(Imagery, APartlyOverlappingColorRasterLeavesNoBlackPixels) {
    OVERFLIGHT_SHARED_FILE(dem, "paired/olinda/olinda_dem_utm25s.tif");
    test::ScratchDir dir;
    const DataSet plain = load_terrain(dem);
    ASSERT_TRUE(plain.info.georeferenced);
    // A grey raster at a third of the DEM's pixel over its western half, and
    // as far again beyond its western edge.
    const std::array<double, 6>& gt = plain.info.geotransform;
    const int cols = 3 * plain.terrain.cols() / 2, rows = 3 * plain.terrain.rows();
    Image2D<float> grey(2 * cols, rows);
    for (int r = 0; r < rows; ++r)
        for (int c = 0; c < 2 * cols; ++c) grey.at(c, r) = float(80 + 120 * (((r / 4) + (c / 4)) % 2));
    grey.at(0, 0) = 0.0f; // off the DEM: the 8-bit stretch maps 0..200, so the pattern stays grey, not black
    RasterGeoreference g;
    g.geotransform = std::array<double, 6>{gt[0] - gt[1] * cols / 3.0, gt[1] / 3.0, 0, gt[3], 0, gt[5] / 3.0};
    g.crs = plain.info.crs_wkt;
    const std::string color = dir / "west.tif";
    write_geotiff(color, grey, g);
    LoadOptions options;
    options.color_path = color;
    const DataSet d = load_terrain(dem, options);
    ASSERT_NE(d.terrain.imagery(), nullptr);
    EXPECT_NEAR(d.terrain.imagery()->coverage(), 0.5, 0.05);
    // Looking across the boundary between the covered and the uncovered half.
    const Terrain& t = d.terrain;
    const double x = 0.5 * t.width(), z = 0.9 * t.depth();
    const Camera cam = test::camera_at({x, t.height_bilinear(float(x), float(z)) + 1500.0, z}, 180.0, -30.0,
                                       1.5 * t.width(), 320, 200);
    gl::HeadlessRenderer r(t, Scene{});
    for (const char* method : {"voxel", "mesh", "raymarch"}) {
        const Frame f = render(d, r, method, cam);
        EXPECT_EQ(black_pixels(f), 0) << method;
    }
}

TEST(Imagery, AColorRasterOffTheDemIsAOneLineError) {
    OVERFLIGHT_SHARED_FILE(dem, "paired/olinda/olinda_dem_utm25s.tif");
    test::ScratchDir dir;
    const DataSet plain = load_terrain(dem);
    const std::array<double, 6>& gt = plain.info.geotransform;
    Image2D<float> grey(64, 64, 100.0f);
    RasterGeoreference g;
    g.geotransform = std::array<double, 6>{gt[0] + 1e6, 10.0, 0, gt[3], 0, -10.0};
    g.crs = plain.info.crs_wkt;
    const std::string color = dir / "far.tif";
    write_geotiff(color, grey, g);
    const test::RunResult r = test::run_overflight("info '" + dem + "' --color '" + color + "'");
    EXPECT_EQ(r.exit_code, 1);
    EXPECT_EQ(r.err, "overflight: " + color + ": color raster does not overlap the DEM\n");
    // Tiled in windows, the same raster is the same error, before any tile is written.
    const std::string tiles = dir / "tiles";
    const test::RunResult t = test::run_overflight("tile '" + dem + "' --color '" + color + "' -o '" + tiles + "' --tile-size 33");
    EXPECT_EQ(t.exit_code, 1);
    EXPECT_EQ(t.err, "overflight: " + color + ": color raster does not overlap the DEM\n");
    EXPECT_FALSE(std::filesystem::exists(std::filesystem::path(tiles) / "index.json"));
}

TEST(Imagery, InfoReportsTheImagerysSizeResolutionAndCoverage) {
    OVERFLIGHT_SHARED_FILE(dem, "paired/olinda/olinda_dem_utm25s.tif");
    OVERFLIGHT_SHARED_FILE(landsat, "paired/olinda/L7_ETMs.tif");
    const test::RunResult r = test::run_overflight("info '" + dem + "' --color '" + landsat + "'");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_NE(r.out.find("imagery_size: 351x351\n"), std::string::npos) << r.out;
    // The DEM's 111 pixels of 90 m over 351 texels.
    EXPECT_NE(r.out.find("imagery_resolution: 28.4"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("imagery_coverage: 0.99"), std::string::npos) << r.out;
}

TEST(Imagery, ImageryBeyondTheMemoryBoundIsDecimatedWithAWarning) {
    OVERFLIGHT_SHARED_FILE(dem, "paired/olinda/olinda_dem_utm25s.tif");
    test::ScratchDir dir;
    const DataSet plain = load_terrain(dem);
    const std::array<double, 6>& gt = plain.info.geotransform;
    // 15 m pixels over the DEM: 666x666 texels, 2.4 MB with their mips.
    const int n = 6 * plain.terrain.cols();
    Image2D<float> grey(n, n);
    for (int r = 0; r < n; ++r)
        for (int c = 0; c < n; ++c) grey.at(c, r) = float(50 + (r * 7 + c * 13) % 200);
    RasterGeoreference g;
    g.geotransform = std::array<double, 6>{gt[0], gt[1] / 6.0, 0, gt[3], 0, gt[5] / 6.0};
    g.crs = plain.info.crs_wkt;
    const std::string color = dir / "fine.tif";
    write_geotiff(color, grey, g);
    LoadOptions options;
    options.color_path = color;
    options.imagery_memory_mib = 1;
    const DataSet d = load_terrain(dem, options);
    ASSERT_NE(d.terrain.imagery(), nullptr);
    EXPECT_EQ(d.terrain.imagery()->level(0).width, n / 2);
    ASSERT_EQ(d.info.warnings.size(), 1u);
    EXPECT_EQ(d.info.warnings[0], color + ": imagery of more than 1 MiB (--imagery-memory-mib); shown decimated by 2 to "
                                          "333x333; for its full resolution tile it (overflight tile DEM --color " +
                                          color + " -o DIR) and view DIR, whose quadtree streams the imagery tiles");
    const test::RunResult r = test::run_overflight("info '" + dem + "' --color '" + color + "' --imagery-memory-mib 0");
    EXPECT_EQ(r.exit_code, 1);
    EXPECT_EQ(r.err, "overflight: --imagery-memory-mib: 0 is not in 1..1048576\n");
}
