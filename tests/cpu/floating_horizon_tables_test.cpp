// The Floating Horizon's per-frame tables (FloatingHorizonTables.h) on a 3x3
// terrain and a 2x4-pixel camera, every expected value worked out by hand
// from Szenberg, Gattass, Carvalho, "An Algorithm for the Visualization of a
// Terrain with Objects", SIBGRAPI 1997 (sec. 5.2 slices, Algorithm 1's
// horizon test, eq. 7) and Guedes, "Integrating Polygonal Objects on Voxel
// Based Terrain Models" (the pitched camera's row slopes).
#include "core/Camera.h"
#include "core/Terrain.h"
#include "raycast/FloatingHorizonTables.h"
#include "raycast/RowSearch.h"

#include "TestCameras.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

using namespace overflight;

namespace {

constexpr float kInf = std::numeric_limits<float>::infinity();

// h_scale 10, v_scale 0.5, y_offset 2: world height 0.5 raw + 2, highest 6.
Terrain three_by_three() {
    const int raw[3][3] = {{0, 4, 0}, {2, 8, 2}, {0, 4, 0}};
    Terrain t(3, 3, 10.0f, 0.5f, 2.0f);
    for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c) t.raw(r, c) = std::uint16_t(raw[r][c]);
    return t;
}

// Eye (5, 4, -20), north of the map, facing south: F = +Z, R = F x Y = -X.
// 2x4 pixels, fp = 2 (fov = 2 atan(1/2)), near 1, far 5.
Camera small_camera(double pitch, Projection projection) {
    return test::two_by_four({5.0, 4.0, -20.0}, pitch, projection);
}

// Slices from d_first to d_last, h_scale 10.
SlicePlacement placement(double d_first, double d_last) {
    SlicePlacement p;
    p.d_first = d_first;
    p.d_last = d_last;
    p.h_scale = 10;
    return p;
}

// fp = 1 / tan(atan(1/2)) is 2 to within rounding, so values derived from it are compared to within 1e-12.
void expect_near(const std::vector<double>& actual, const std::vector<double>& expected) {
    ASSERT_EQ(actual.size(), expected.size());
    for (std::size_t i = 0; i < actual.size(); ++i) EXPECT_NEAR(actual[i], expected[i], 1e-12) << "entry " << i;
}

} // namespace

TEST(FloatingHorizonTables, ViewAxesInGridUnits) {
    const ViewAxes v = view_axes(small_camera(0, Projection::Shear), 10.0);
    EXPECT_DOUBLE_EQ(v.eye_gx, 0.5);
    EXPECT_DOUBLE_EQ(v.eye_gz, -2.0);
    EXPECT_DOUBLE_EQ(v.eye_y, 4.0);
    EXPECT_NEAR(v.fx, 0.0, 1e-15);
    EXPECT_DOUBLE_EQ(v.fz, 1.0);
    EXPECT_DOUBLE_EQ(v.rx, -1.0);
    EXPECT_NEAR(v.rz, 0.0, 1e-15);
}

// One cell apart from d_first while d <= d_last.
TEST(FloatingHorizonTables, SlicesOneCellApart) {
    Slices s;
    place_slices(placement(1, 35), s);
    EXPECT_TRUE(s.uniform);
    EXPECT_EQ(s.step, 10.0);
    EXPECT_EQ(s.d, (std::vector<double>{1, 11, 21, 31}));
    EXPECT_EQ(s.df, (std::vector<float>{1, 11, 21, 31}));
    EXPECT_EQ(s.level, (std::vector<std::uint8_t>{0, 0, 0, 0}));
    EXPECT_EQ(s.even, 4);
}

// Near refinement: a step spans at most near_step_pixels = 1 pixel, d / fp_h
// with fp_h = 2, between 1/8 cell (1.25) and one cell (10).
TEST(FloatingHorizonTables, SlicesNarrowNearTheEye) {
    SlicePlacement p = placement(1, 35);
    p.fp_h = 2;
    p.near_step_pixels = 1;
    Slices s;
    place_slices(p, s);
    EXPECT_FALSE(s.uniform);
    // Steps 1.25, 1.25, 1.75, 2.625, 3.9375, 5.90625, 8.859375 (d/2), then 10.
    EXPECT_EQ(s.d, (std::vector<double>{1, 2.25, 3.5, 5.25, 7.875, 11.8125, 17.71875, 26.578125}));
    EXPECT_EQ(s.df[7], 26.578125f);
    EXPECT_EQ(s.level, std::vector<std::uint8_t>(8, 0));
    EXPECT_EQ(s.even, 0); // the first step is finer than a cell
}

// Distance LOD: a pixel spans lod_pixels * 2^L cells at d = fp_h h_scale
// lod_pixels 2^L = 5 * 2^L (fp_h = 1): level 1 from d = 10, level 2 from
// d = 20 (the deepest of lod_levels = 2), each level's step 2^L cells.
TEST(FloatingHorizonTables, SlicesStepThroughLodLevels) {
    SlicePlacement p = placement(1, 60);
    p.fp_h = 1;
    p.lod = true;
    p.lod_levels = 2;
    p.lod_pixels = 0.5;
    Slices s;
    place_slices(p, s);
    EXPECT_FALSE(s.uniform);
    EXPECT_EQ(s.d, (std::vector<double>{1, 11, 31}));
    EXPECT_EQ(s.level, (std::vector<std::uint8_t>{0, 1, 2}));
    EXPECT_EQ(s.even, 1); // slice 0 steps one cell; slice 1 (level 1) two
    // A longer level 0 (fp_h = 10: level 1 from d = 100): its slices one cell
    // apart at d_first + h_scale k, as the uniform slices, the block cast's.
    p.fp_h = 10;
    p.d_last = 250;
    place_slices(p, s);
    EXPECT_EQ(s.even, 10);
    for (int k = 0; k < 10; ++k) EXPECT_EQ(s.d[std::size_t(k)], 1 + 10.0 * k) << k;
    EXPECT_EQ(s.level[9], 0);
    EXPECT_EQ(s.level[10], 1);
}

// a_k = v_scale / d_k, b_k = (y_offset - eye_y) / d_k; the highest sample
// (raw 8, world 6) at slice k has slope (6 - 4) / d_k: 1, 0.5, 0.25, and
// smax_k is the largest from k on, rounded up.
TEST(FloatingHorizonTables, SliceSlopesFoldInOneOverD) {
    const Terrain t = three_by_three();
    ASSERT_EQ(t.max_height(), 6.0f);
    SliceSlopes s;
    slice_slopes({2, 4, 8}, t, t.max_height(), 4.0, s);
    EXPECT_EQ(s.a, (std::vector<float>{0.25f, 0.125f, 0.0625f}));
    EXPECT_EQ(s.b, (std::vector<float>{-1.0f, -0.5f, -0.25f}));
    EXPECT_EQ(s.smax, (std::vector<float>{std::nextafter(1.0f, kInf), std::nextafter(0.5f, kInf),
                                          std::nextafter(0.25f, kInf)}));
    // The horizon test of Algorithm 1: raw 8 at slice 0 is at slope 8 a + b = 1.
    EXPECT_EQ(8.0f * s.a[0] + s.b[0], 1.0f);
}

// eq. 7: (f - f n / d) / (f - n) with n = 1, f = 5.
TEST(FloatingHorizonTables, SliceWindowDepthsAreTheDepthVector) {
    const Camera cam = small_camera(0, Projection::Shear);
    Slices uniform;
    uniform.d = {1, 2, 3, 4};
    uniform.uniform = true;
    uniform.step = 1;
    std::vector<float> depth;
    slice_window_depths(cam, uniform, depth);
    ASSERT_EQ(depth.size(), 4u);
    EXPECT_FLOAT_EQ(depth[0], 0.0f);
    EXPECT_FLOAT_EQ(depth[1], 0.625f);
    EXPECT_FLOAT_EQ(depth[2], 0.8333333f);
    EXPECT_FLOAT_EQ(depth[3], 0.9375f);
    Slices varying;
    varying.d = {2, 4};
    varying.uniform = false;
    slice_window_depths(cam, varying, depth);
    EXPECT_EQ(depth.size(), 2u);
    EXPECT_FLOAT_EQ(depth[0], 0.625f);
    EXPECT_FLOAT_EQ(depth[1], 0.9375f);
}

// Rows bottom-up: v = -1.5, -0.5, 0.5, 1.5, m = (v + fp tan p) / fp.
TEST(FloatingHorizonTables, ShearRowsShiftWithPitch) {
    Rows rows;
    shear_rows(small_camera(0, Projection::Shear), rows);
    EXPECT_EQ(rows.count, 4);
    EXPECT_TRUE(rows.even);
    EXPECT_EQ(rows.m, (std::vector<float>{-0.75f, -0.25f, 0.25f, 0.75f, kInf}));
    shear_rows(small_camera(45, Projection::Shear), rows); // shift fp tan 45 = 2
    ASSERT_EQ(rows.m.size(), 5u);
    EXPECT_FLOAT_EQ(rows.m[0], 0.25f);
    EXPECT_FLOAT_EQ(rows.m[3], 1.75f);
    EXPECT_EQ(rows.m[4], kInf);
}

// Pitch -60: w = cos p - (v/fp) sin p = 1/2 + (sqrt 3 / 2)(v / 2) and
// m = (sin p + (v/fp) cos p) / w per image row (top-down, v = 1.5 .. -1.5):
// w = 1.1495, 0.7165, 0.2835, -0.1495. Rows with w < w_max / 4 = 0.2874 (the
// bottom two, j = 0 and 1) are not cast.
TEST(FloatingHorizonTables, TiltRowsCutTheSteepOnes) {
    TiltRows t;
    tilt_rows(small_camera(-60, Projection::Tilt), t);
    ASSERT_EQ(t.w.size(), 4u);
    EXPECT_NEAR(t.w[0], 1.1495191, 1e-7);
    EXPECT_NEAR(t.w[1], 0.7165064, 1e-7);
    EXPECT_NEAR(t.w[2], 0.2834936, 1e-7);
    EXPECT_NEAR(t.w[3], -0.1495191, 1e-7);
    EXPECT_NEAR(t.m[0], -0.4271573, 1e-7);
    EXPECT_NEAR(t.m[1], -1.0342203, 1e-7);
    EXPECT_EQ(t.j_lo, 2);
    EXPECT_EQ(t.j_hi, 4);
    EXPECT_NEAR(t.w_min, 0.7165064, 1e-7);
    EXPECT_NEAR(t.w_max, 1.1495191, 1e-7);
    Rows rows;
    tilt_cast_rows(t, rows); // bottom-up: j = 2 (image row 1), j = 3 (image row 0)
    EXPECT_EQ(rows.count, 2);
    EXPECT_FALSE(rows.even);
    EXPECT_EQ(rows.m, (std::vector<float>{float(t.m[1]), float(t.m[0]), kInf}));

    tilt_rows(small_camera(0, Projection::Tilt), t); // level: the shear rows, all cast
    EXPECT_EQ(t.j_lo, 0);
    EXPECT_EQ(t.j_hi, 4);
    EXPECT_EQ(t.w_min, 1.0);
    EXPECT_EQ(t.w_max, 1.0);
    expect_near(t.m, {0.75, 0.25, -0.25, -0.75});
}

TEST(FloatingHorizonTables, ColumnPlanes) {
    std::vector<double> a;
    shear_column_planes(small_camera(0, Projection::Shear), a); // u / fp, u = -0.5, 0.5
    expect_near(a, {-0.25, 0.25});
    guedes_column_planes(small_camera(-60, Projection::Tilt), a); // u / (fp cos p)
    expect_near(a, {-0.5, 0.5});
    // Level tilt: w = 1, planes at kTiltPlanes = 2 per pixel: fp_h = 4; the
    // pixels reach a = +-(W/2)/fp = +-0.5, so ceil(2 * 0.5 * 4) = 4 planes at
    // (i + 0.5 - 2) / 4.
    TiltRows t;
    tilt_rows(small_camera(0, Projection::Tilt), t);
    EXPECT_NEAR(tilt_column_planes(small_camera(0, Projection::Tilt), t, a), 4.0, 1e-12);
    expect_near(a, {-0.375, -0.125, 0.125, 0.375});
}

// The eye at grid (0.5, -2) facing +Z (R = -X), slices d = 10, 20, 30, 40
// (grid z = -2 + d / 10: -1, 0, 1, 2). Plane a goes sideways by -a d / 10.
//   a = 0:     x stays 0.5; on the map for d in [20, 40]: slices 1..3;
//   a = -0.25: x = 0.5 + d/40 <= 1.5: the same slices;
//   a = 0.25:  x = 0.5 - d/40 >= 0 only up to d = 20: the corner, slice 1;
//   a = 2:     x = 0.5 - d/5 leaves the map at d = 2.5: no slice.
TEST(FloatingHorizonTables, ColumnsClippedToTheTerrain) {
    const Terrain t = three_by_three();
    const ViewAxes view = view_axes(small_camera(0, Projection::Shear), 10.0);
    Columns cols;
    cols.a = {0.0, -0.25, 0.25, 2.0};
    Slices slices;
    slices.d = {10, 20, 30, 40};
    clip_columns(view, t, slices, cols);
    EXPECT_EQ(cols.k0, (std::vector<int>{1, 1, 1, 0}));
    EXPECT_EQ(cols.k1, (std::vector<int>{4, 4, 2, 0}));
    EXPECT_NEAR(cols.ux[0], 0.0, 1e-15);
    EXPECT_DOUBLE_EQ(cols.uz[0], 0.1);
    EXPECT_DOUBLE_EQ(cols.ux[1], 0.025);
    EXPECT_DOUBLE_EQ(cols.ux[3], -0.2);
}

// The evenly spaced slices' bounds come from their spacing and a short walk,
// the rest from bisection: both give every column the slices bisection over
// all of them gives. A 200-cell square (h_scale 10) seen from outside it and
// from within, slices one cell apart up to d = 5000, then LOD's coarser ones.
TEST(FloatingHorizonTables, ColumnsClippedAlikeBySpacingAndBisection) {
    const Terrain t(200, 200, 10.0f, 1.0f, 0.0f);
    SlicePlacement p = placement(0.5, 20000);
    p.fp_h = 500;
    p.lod = true;
    p.lod_levels = 4;
    Slices spaced;
    place_slices(p, spaced);
    ASSERT_GT(spaced.even, 400);
    ASSERT_LT(spaced.even, int(spaced.d.size()));
    Slices bisected = spaced;
    bisected.even = 0;
    for (const double eye_x : {-300.0, 1000.0, 2500.0}) {
        Camera camera = small_camera(0, Projection::Shear);
        camera.eye = {eye_x, 4.0, eye_x * 0.7};
        for (const double heading : {0.0, 33.0, 90.0, 200.0}) {
            camera.heading = heading;
            const ViewAxes view = view_axes(camera, 10.0);
            Columns by_spacing, by_bisection;
            for (int c = -400; c <= 400; ++c) by_spacing.a.push_back(c / 401.0);
            by_bisection.a = by_spacing.a;
            clip_columns(view, t, spaced, by_spacing);
            clip_columns(view, t, bisected, by_bisection);
            EXPECT_EQ(by_spacing.k0, by_bisection.k0) << eye_x << " " << heading;
            EXPECT_EQ(by_spacing.k1, by_bisection.k1) << eye_x << " " << heading;
        }
    }
}

// Rows -0.75, -0.25, 0.25, 0.75: RowSearch's m0 = -0.75, 1/step = 2. Slice
// a = 0.25, b = -1: ga = a * 2 = 0.5, gb = (b - m0) * 2 + 1 = 0.5, in
// 2^-24 units; the guess (raw ga + gb) >> 24 is RowSearch's row.
TEST(FloatingHorizonTables, SliceGuessesStartRowSearchWithinARow) {
    Rows rows;
    shear_rows(small_camera(0, Projection::Shear), rows);
    SliceSlopes slopes;
    slopes.a = {0.25f};
    slopes.b = {-1.0f};
    std::vector<SliceGuess> g;
    slice_guesses(slopes, rows, g);
    ASSERT_EQ(g.size(), 1u);
    EXPECT_EQ(g[0].ga, 1 << 23);
    EXPECT_EQ(g[0].gb, 1 << 23);
    EXPECT_EQ(g[0].a, 0.25f);
    EXPECT_EQ(g[0].b, -1.0f);
    const RowSearch search(rows.m.data(), rows.count);
    for (int raw : {2, 8}) { // sigma -0.5: row 1 (-0.25); sigma 1: above the top row (4)
        const float sigma = float(raw) * g[0].a + g[0].b;
        const std::int64_t guess = (std::int64_t(raw) * g[0].ga + g[0].gb) >> kGuessBits;
        EXPECT_EQ(guess, search.first_not_below(sigma)) << "raw " << raw;
    }
    EXPECT_EQ(search.first_not_below(-0.5f), 1);
    EXPECT_EQ(search.first_not_below(1.0f), 4);
}

// far 5 along the longest ray, 0.1 % over: shear (1, 0.5, 0.75) per unit of
// depth, tilt (1, 0.5, 1) (the image corner).
TEST(FloatingHorizonTables, FogReachCoversTheLongestRay) {
    Rows rows;
    const Camera shear = small_camera(0, Projection::Shear);
    shear_rows(shear, rows);
    EXPECT_NEAR(shear_fog_reach(shear, rows), 5.0 * std::sqrt(1.8125) * 1.001, 1e-5);
    EXPECT_NEAR(tilt_fog_reach(small_camera(-60, Projection::Tilt)), 5.0 * 1.5 * 1.001, 1e-5);
}
