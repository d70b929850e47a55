// The Floating Horizon's speed-ups must not change a single pixel. Skipping
// runs of slices with the max-height pyramid (SliceRunBound): a run is skipped
// only when every sample in it stays below the horizon, where Algorithm 1
// (Szenberg, Gattass, Carvalho, "An Algorithm for the Visualization of a
// Terrain with Objects", SIBGRAPI 1997) paints nothing. The cast compiled for
// x86-64-v3 (CastKernel): the same operations as the portable one.
#include "TestSupport.h"

#include "core/Camera.h"
#include "core/DemoIsland.h"
#include "io/LoadTerrain.h"
#include "raycast/FloatingHorizon.h"
#include "raycast/FloatingHorizonCast.h"
#include "raycast/HeightPyramid.h"
#include "raycast/SliceRunBound.h"

#include "TestCameras.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <numbers>
#include <random>

using namespace overflight;

namespace {

constexpr double kOne = 4294967296.0; // 32.32 fixed point

// The nearest sample of a 32.32 position offset by half a sample, as the caster reads it.
std::uint16_t nearest(const Terrain& t, std::int64_t gx, std::int64_t gz) {
    return t.raw(int(gz >> 32), int(gx >> 32));
}

// A level view from (512, 10, 8) looking south (+Z), across walls that run
// along X.
Camera looking_south(int width, int height, double far) {
    Camera cam;
    cam.eye = {512.0, 10.0, 8.0};
    cam.heading = 0;
    cam.pitch = 0;
    cam.width = width;
    cam.height = height;
    cam.far = far;
    return cam;
}

// Renders a sweep of views with and without skipping: every pixel's color
// and depth must be bit-identical. Returns the samples skipping spared over
// the sweep (so that the comparison is not between two casts that skipped
// nothing); every view must show terrain.
// `lod`: with the distance LOD (and its first coarser level close to the
// eye, so that most slices sample levels >= 1), whose slices are unevenly
// spaced.
long long expect_same_with_and_without_skipping(const DataSet& ds, Projection proj, SurfaceModel surface,
                                                bool lod = false) {
    FloatingHorizon fh(ds.terrain);
    RaycastOptions skip, full;
    skip.surface = full.surface = surface;
    skip.lod = full.lod = lod;
    skip.lod_pixels = full.lod_pixels = 0.05;
    full.skip_runs = false;
    ColorImage c1, c2;
    DepthImage d1, d2;
    RaycastStats s1, s2;
    long long spared = 0;
    for (double heading = 0; heading < 360; heading += 45)
        for (double pitch : {-30.0, -12.0, 0.0, 15.0}) {
            const Camera cam = test::across_terrain(ds.terrain, heading, pitch, proj);
            fh.render(cam, ds.environment, skip, c1, d1, &s1);
            fh.render(cam, ds.environment, full, c2, d2, &s2);
            EXPECT_EQ(0, std::memcmp(c1.pixels.data(), c2.pixels.data(), c1.pixels.size() * sizeof(Rgb8)))
                << "color, heading " << heading << " pitch " << pitch;
            EXPECT_EQ(0, std::memcmp(d1.pixels.data(), d2.pixels.data(), d1.pixels.size() * sizeof(float)))
                << "depth, heading " << heading << " pitch " << pitch;
            EXPECT_GT(s1.pixels_painted, 0) << "heading " << heading << " pitch " << pitch;
            EXPECT_LE(s1.samples_visited, s2.samples_visited);
            spared += s2.samples_visited - s1.samples_visited;
        }
    return spared;
}

} // namespace

// Runs in every direction, of both lengths the caster uses, from random
// starts: the bound is at least every nearest sample of the run.
TEST(SliceRunBound, BoundsEveryNearestSampleOfTheRun) {
    const DataSet ds = make_demo_island({257});
    const Terrain& t = ds.terrain;
    const HeightPyramid pyramid(t, 12);
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> angle(0.0, 2.0 * std::numbers::pi), stretch(1.0, 3.0), pos(0.0, 1.0);
    long long runs = 0;
    for (int trial = 0; trial < 4000; ++trial) {
        const int run = trial % 2 ? 32 : 8;
        const double a = angle(rng), len = stretch(rng); // samples per slice: 1 / cos(theta) >= 1
        const std::int64_t sx = std::llround(len * std::cos(a) * kOne), sz = std::llround(len * std::sin(a) * kOne);
        const SliceRunBound bound(pyramid, run, sx, sz);
        ASSERT_TRUE(bound.usable());
        // A start such that the whole run stays on the grid.
        const double span = (run - 1) * len, lo = span + 1, hi_x = t.cols() - 2 - span, hi_z = t.rows() - 2 - span;
        if (hi_x <= lo || hi_z <= lo) continue;
        const std::int64_t gx = std::llround((lo + pos(rng) * (hi_x - lo) + 0.5) * kOne);
        const std::int64_t gz = std::llround((lo + pos(rng) * (hi_z - lo) + 0.5) * kOne);
        const std::uint16_t h = bound.max_height(gx, gz);
        std::uint16_t highest = 0;
        for (int q = 0; q < run; ++q) highest = std::max(highest, nearest(t, gx + q * sx, gz + q * sz));
        ASSERT_GE(h, highest) << "trial " << trial;
        ++runs;
    }
    EXPECT_GT(runs, 3000);
}

// Bilinear: the four samples around every position of the run (stepped in
// floating point, as the caster does), or no bound at all near the edge.
TEST(SliceRunBound, BilinearBoundsTheSamplesAroundTheRun) {
    const DataSet ds = make_demo_island({257});
    const Terrain& t = ds.terrain;
    const HeightPyramid pyramid(t, 12);
    std::mt19937 rng(11);
    std::uniform_real_distribution<double> angle(0.0, 2.0 * std::numbers::pi), stretch(1.0, 3.0), pos(0.0, 1.0);
    int bounded = 0;
    for (int trial = 0; trial < 4000; ++trial) {
        const double a = angle(rng), len = stretch(rng), sx = len * std::cos(a), sz = len * std::sin(a);
        const SliceRunBound bound(pyramid, 8, std::llround(sx * kOne), std::llround(sz * kOne), Footprint::Bilinear);
        ASSERT_TRUE(bound.usable());
        double gx = 7 * len + pos(rng) * (t.cols() - 1 - 14 * len), gz = 7 * len + pos(rng) * (t.rows() - 1 - 14 * len);
        const std::uint16_t h = bound.max_height(std::llround(gx * kOne), std::llround(gz * kOne));
        std::uint16_t highest = 0;
        bool edge = false;
        for (int q = 0; q < 8; ++q, gx += sx, gz += sz) {
            const int c0 = std::clamp(int(gx), 0, t.cols() - 2), r0 = std::clamp(int(gz), 0, t.rows() - 2);
            edge = edge || c0 == 0 || r0 == 0 || c0 == t.cols() - 2 || r0 == t.rows() - 2;
            for (int dr = 0; dr < 2; ++dr)
                for (int dc = 0; dc < 2; ++dc) highest = std::max(highest, t.raw(r0 + dr, c0 + dc));
        }
        ASSERT_GE(h, highest) << "trial " << trial;
        if (edge) {
            EXPECT_EQ(h, 65535) << "trial " << trial;
        }
        bounded += h < 65535;
    }
    EXPECT_GT(bounded, 3000);
}

// Random boxes of every shape up to 2^10 samples: the bound is at least every
// sample in the box, and no higher than the box's own level-L cells allow.
TEST(SliceRunBound, BoxBoundsEverySampleOfTheBox) {
    const DataSet ds = make_demo_island({257});
    const Terrain& t = ds.terrain;
    const HeightPyramid pyramid(t, 12);
    std::mt19937 rng(5);
    std::uniform_int_distribution<int> size_log(0, 8), corner(0, t.cols() - 1);
    for (int trial = 0; trial < 2000; ++trial) {
        const int w = std::uniform_int_distribution<int>(1, 1 << size_log(rng))(rng);
        const int h = std::uniform_int_distribution<int>(1, 1 << size_log(rng))(rng);
        const int x0 = std::min(corner(rng), t.cols() - w), z0 = std::min(corner(rng), t.rows() - h);
        const int x1 = x0 + w - 1, z1 = z0 + h - 1;
        std::uint16_t highest = 0;
        for (int z = z0; z <= z1; ++z)
            for (int x = x0; x <= x1; ++x) highest = std::max(highest, t.raw(z, x));
        ASSERT_GE(box_max_height(pyramid, x0, x1, z0, z1), highest) << "trial " << trial;
    }
    // A single sample: the level-1 cell holding it.
    EXPECT_EQ(box_max_height(pyramid, 3, 3, 5, 5),
              std::max({t.raw(4, 2), t.raw(4, 3), t.raw(5, 2), t.raw(5, 3)}));
    // Wider than the pyramid's coarsest level: no bound.
    const HeightPyramid shallow(t, 2);
    EXPECT_EQ(box_max_height(shallow, 0, 4, 0, 0), 65535);
    EXPECT_LT(box_max_height(shallow, 0, 3, 0, 0), 65535);
}

TEST(SliceRunBound, NotUsableWithoutACoarseEnoughLevel) {
    Terrain t(5, 5, 1.0f);
    const HeightPyramid pyramid(t, 12); // 3x3, 2x2, 1x1: up to 8 samples square
    EXPECT_TRUE(SliceRunBound(pyramid, 4, std::llround(kOne), 0).usable());
    EXPECT_FALSE(SliceRunBound(pyramid, 32, std::llround(kOne), 0).usable());
    EXPECT_FALSE(SliceRunBound(pyramid, 0, std::llround(kOne), 0).usable());
}

// The x86-64-v4 cast gathers level 0 as {color, height} records: each
// sample's packed color in the low half, its raw height in the high half, kept
// up to date when the colors change.
TEST(CastTerrain, RecordsHoldEachSamplesColorAndRawHeight) {
    Terrain t(2, 3, 1.0f);
    const std::uint16_t raw[6] = {0, 1, 300, 65535, 7, 40000};
    for (int i = 0; i < 6; ++i) {
        t.raw(i / 3, i % 3) = raw[i];
        t.color(i / 3, i % 3) = Rgb8{std::uint8_t(i), std::uint8_t(10 * i), 200};
    }
    CastTerrain ct(t);
    EXPECT_TRUE(ct.records.empty()); // built on demand only
    ct.prepare_records();
    ASSERT_EQ(ct.records.size(), 6u);
    EXPECT_EQ(ct.records[0], 0x00000000'00C80000u);
    EXPECT_EQ(ct.records[2], 0x0000012C'00C81402u);
    EXPECT_EQ(ct.records[3], 0x0000FFFF'00C81E03u);
    EXPECT_EQ(ct.records[5], 0x00009C40'00C83205u);
    const std::vector<Rgb8> lit(6, Rgb8{9, 8, 7});
    ct.set_colors(&lit);
    ASSERT_EQ(ct.records.size(), 6u);
    EXPECT_EQ(ct.records[2], 0x0000012C'00070809u);
    EXPECT_EQ(ct.records[4], 0x00000007'00070809u);
}

TEST(FloatingHorizonRunSkipping, SameImageAsWithoutOnTheDemo) {
    const DataSet ds = make_demo_island({257});
    for (SurfaceModel surface : {SurfaceModel::Blocks, SurfaceModel::Bilinear}) {
        EXPECT_GT(expect_same_with_and_without_skipping(ds, Projection::Shear, surface), 0);
        EXPECT_GT(expect_same_with_and_without_skipping(ds, Projection::Tilt, surface), 0);
    }
}

TEST(FloatingHorizonRunSkipping, SameImageAsWithoutOnCraterLake) {
    OVERFLIGHT_SHARED_FILE(path, "bt/crater_0513.bt");
    const DataSet ds = load_terrain(path);
    EXPECT_GT(expect_same_with_and_without_skipping(ds, Projection::Shear, SurfaceModel::Blocks), 0);
    EXPECT_GT(expect_same_with_and_without_skipping(ds, Projection::Shear, SurfaceModel::Bilinear), 0);
}

// The distance LOD's slices double their spacing with each coarser level:
// its runs are bounded from the box of the samples they read, widened to the
// cells of their level, and skipped only where no sample of the level rises
// above the horizon. Same pixels as without skipping.
TEST(FloatingHorizonRunSkipping, SameImageAsWithoutOnTheLodLevels) {
    const DataSet ds = make_demo_island({257});
    for (SurfaceModel surface : {SurfaceModel::Blocks, SurfaceModel::Bilinear}) {
        EXPECT_GT(expect_same_with_and_without_skipping(ds, Projection::Shear, surface, true), 0);
        EXPECT_GT(expect_same_with_and_without_skipping(ds, Projection::Tilt, surface, true), 0);
    }
}

// A literal terrain: a low plain, a wall across the view 50 samples ahead
// and a ridge at the far edge that keeps the columns casting past the wall.
// With the LOD (levels 1-4 from about 80 samples on), the runs over the
// plain behind the wall are skipped on every level, and the image is the
// same bits as casting every slice.
TEST(FloatingHorizonRunSkipping, SkipsBehindAWallOnTheLodLevels) {
    Terrain t(1025, 1025, 1.0f);
    for (int r = 0; r < t.rows(); ++r)
        for (int c = 0; c < t.cols(); ++c) t.raw(r, c) = r >= 58 && r < 62 ? 12 : r >= 1000 ? 200 : 1;
    const DataSet ds{std::move(t), {}, {}};
    FloatingHorizon fh(ds.terrain);
    const Camera cam = looking_south(160, 90, 1100);
    RaycastOptions skip, full;
    skip.lod = full.lod = true;
    skip.lod_pixels = full.lod_pixels = 0.3;
    full.skip_runs = false;
    ColorImage c1, c2;
    DepthImage d1, d2;
    RaycastStats s1, s2;
    fh.render(cam, ds.environment, skip, c1, d1, &s1);
    fh.render(cam, ds.environment, full, c2, d2, &s2);
    EXPECT_EQ(0, std::memcmp(c1.pixels.data(), c2.pixels.data(), c1.pixels.size() * sizeof(Rgb8)));
    EXPECT_EQ(0, std::memcmp(d1.pixels.data(), d2.pixels.data(), d1.pixels.size() * sizeof(float)));
    EXPECT_GT(s1.pixels_painted, 0);
    EXPECT_LT(s1.samples_visited * 3, s2.samples_visited) << s1.samples_visited << " vs " << s2.samples_visited;
}

// Skipping reads fewer samples (not a time; on this small view a quarter fewer,
// on the bench's 4097^2 view a quarter as many).
TEST(FloatingHorizonRunSkipping, ReadsFewerSamples) {
    const DataSet ds = make_demo_island({257});
    FloatingHorizon fh(ds.terrain);
    const Camera cam = test::across_terrain(ds.terrain, 0, -12, Projection::Shear);
    RaycastOptions full;
    full.skip_runs = false;
    ColorImage c;
    DepthImage d;
    RaycastStats with, without;
    fh.render(cam, ds.environment, {}, c, d, &with);
    fh.render(cam, ds.environment, full, c, d, &without);
    EXPECT_LT(with.samples_visited * 5, without.samples_visited * 4)
        << with.samples_visited << " vs " << without.samples_visited;
}

// With run skipping on its levels the distance LOD reads fewer samples than
// the exact cast (it used to read more: its uneven slices were all cast).
// Not a time; on this view 9 % fewer.
TEST(FloatingHorizonRunSkipping, LodReadsFewerSamplesThanTheExactCast) {
    const DataSet ds = make_demo_island({257});
    FloatingHorizon fh(ds.terrain);
    RaycastOptions lod;
    lod.lod = true;
    lod.lod_pixels = 0.1;
    ColorImage c;
    DepthImage d;
    const Camera cam = test::across_terrain(ds.terrain, 0, -12, Projection::Shear);
    RaycastStats exact, coarse;
    fh.render(cam, ds.environment, {}, c, d, &exact);
    fh.render(cam, ds.environment, lod, c, d, &coarse);
    EXPECT_LT(coarse.samples_visited, exact.samples_visited) << coarse.samples_visited << " vs " << exact.samples_visited;
}

// The block cast compiled for x86-64-v3 and the one for x86-64-v4 (its
// columns in lockstep, CastKernel) paint what the portable one paints, bit
// for bit, in every mode that reaches them, visiting the same samples. Views
// large enough that one rounding done differently (an FMA) shows; headings
// off the grid's axes and eyes off the terrain (columns that start at
// different slices).
TEST(FloatingHorizonCastKernels, SameImageOnEveryInstructionSet) {
    if (!cast_kernel_available(CastKernel::X86_64_v3)) GTEST_SKIP() << "no x86-64-v3 on this CPU";
    const DataSet ds = make_demo_island({1025});
    FloatingHorizon fh(ds.terrain);
    ColorImage c1, c2;
    DepthImage d1, d2;
    RaycastStats s1, s2;
    for (CastKernel kernel : {CastKernel::X86_64_v3, CastKernel::X86_64_v4}) {
        if (!cast_kernel_available(kernel)) continue;
        for (bool lod : {false, true}) // the LOD: uneven slices, run skipping on its levels
        for (Projection proj : {Projection::Shear, Projection::Tilt})
            for (SurfaceModel surface : {SurfaceModel::Blocks, SurfaceModel::Bilinear})
                for (double heading = 7.5; heading < 360; heading += 45)
                    for (double pitch : {-30.0, 0.0, 15.0})
                        for (bool off_terrain : {false, true}) {
                        RaycastOptions portable, fast;
                        portable.surface = fast.surface = surface;
                        portable.lod = fast.lod = lod;
                        portable.lod_pixels = fast.lod_pixels = 0.1;
                        portable.kernel = CastKernel::Portable;
                        fast.kernel = kernel;
                        Camera cam = test::across_terrain(ds.terrain, heading, pitch, proj);
                        cam.width = 960;
                        cam.height = 540;
                        if (off_terrain) { // behind the grid's edge, looking across it
                            const glm::dvec3 back = 0.5 * std::max(ds.terrain.width(), ds.terrain.depth()) * cam.forward();
                            cam.eye.x -= back.x;
                            cam.eye.z -= back.z;
                        }
                        fh.render(cam, ds.environment, portable, c1, d1, &s1);
                        fh.render(cam, ds.environment, fast, c2, d2, &s2);
                        const std::string what = std::string("kernel ") + (kernel == CastKernel::X86_64_v3 ? "v3" : "v4") +
                                                 ", lod " + std::to_string(lod) + " heading " +
                                                 std::to_string(heading) + " pitch " + std::to_string(pitch) +
                                                 (off_terrain ? " off the terrain" : "");
                        EXPECT_EQ(0, std::memcmp(c1.pixels.data(), c2.pixels.data(), c1.pixels.size() * sizeof(Rgb8)))
                            << "color, " << what;
                        EXPECT_EQ(0, std::memcmp(d1.pixels.data(), d2.pixels.data(), d1.pixels.size() * sizeof(float)))
                            << "depth, " << what;
                        EXPECT_EQ(s1.samples_visited, s2.samples_visited) << what;
                        // Terrain in view: the images have something to disagree on.
                        EXPECT_GT(s2.pixels_painted, 0) << what;
                    }
    }
}

// The 16-lane cast paints only a slice index's low 8 bits beside the color
// and restores the index from the row below, keeping aside each rise that
// comes 256 slices or more after its column's last one: walls across the
// view at gaps of 255, 256, 257, 300 and 600 one-cell slices behind each
// other, each rising above the previous one (the view looks along Z, across
// the walls, so every image column reaches a wall at the same slice), must
// paint the same slices (window depths) as the portable cast.
TEST(FloatingHorizonCastKernels, SameSlicesAfterLongGaps) {
    if (!cast_kernel_available(CastKernel::X86_64_v3)) GTEST_SKIP() << "no x86-64-v3 on this CPU";
    Terrain t(2049, 1025, 1.0f); // rows (Z), columns (X)
    for (int r = 0; r < t.rows(); ++r)
        for (int c = 0; c < t.cols(); ++c) t.raw(r, c) = 1;
    // Each wall's lowest top seen from the eye (height 10, Z = 8) at a slope
    // above the previous wall's highest (+2), all within the view.
    const int walls[] = {40, 295, 551, 808, 1108, 1708};
    const double slopes[] = {0.02, 0.10, 0.11, 0.12, 0.13, 0.14};
    for (int w = 0; w < 6; ++w) {
        const int height = int(std::ceil(10.0 + slopes[w] * (walls[w] - 8)));
        for (int r = walls[w]; r < walls[w] + 3; ++r)
            for (int c = 0; c < t.cols(); ++c) t.raw(r, c) = std::uint16_t(height + c % 3);
    }
    const DataSet ds{std::move(t), {}, {}};
    FloatingHorizon fh(ds.terrain);
    Camera cam = looking_south(480, 270, 2040);
    for (CastKernel kernel : {CastKernel::X86_64_v3, CastKernel::X86_64_v4}) {
        if (!cast_kernel_available(kernel)) continue;
        for (int width : {480, 41}) { // whole groups of 16 lanes, and a partial one
            cam.width = width;
            RaycastOptions portable, fast;
            portable.kernel = CastKernel::Portable;
            fast.kernel = kernel;
            ColorImage c1, c2;
            DepthImage d1, d2;
            fh.render(cam, ds.environment, portable, c1, d1);
            fh.render(cam, ds.environment, fast, c2, d2);
            EXPECT_EQ(0, std::memcmp(c1.pixels.data(), c2.pixels.data(), c1.pixels.size() * sizeof(Rgb8)))
                << "width " << width;
            EXPECT_EQ(0, std::memcmp(d1.pixels.data(), d2.pixels.data(), d1.pixels.size() * sizeof(float)))
                << "width " << width;
            // Every wall shows above the horizon, each painted from one slice:
            // the middle column's depths there are the six walls' and sky (at
            // 41 columns the focal length is too short to part them).
            if (width < 480) continue;
            std::vector<float> seen;
            for (int y = 0; y < cam.height / 2 - 1; ++y) seen.push_back(d2.at(width / 2, y));
            std::sort(seen.begin(), seen.end());
            seen.erase(std::unique(seen.begin(), seen.end()), seen.end());
            EXPECT_EQ(seen.size(), std::size(walls) + 1) << "width " << width;
        }
    }
}
