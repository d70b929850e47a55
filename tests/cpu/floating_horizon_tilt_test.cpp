// The tilted camera's steep rows: rays that point too far down (past the
// vertical, under the eye) or up for the vertical planes the Floating Horizon
// casts (TiltRows: w < w_max / 4) are handed to the reference ray marcher,
// pixel by pixel, for both tilt methods (exact reprojection and Guedes,
// "Integrating Polygonal Objects on Voxel Based Terrain Models",
// Algorithm 1). Those pixels are the marcher's own, bit for bit, and
// RaycastStats::fallback_pixels counts them.
#include "core/Camera.h"
#include "core/DemoIsland.h"
#include "raycast/FloatingHorizon.h"
#include "raycast/FloatingHorizonTables.h"
#include "raycast/RayMarcher.h"

#include "TestCameras.h"

#include <gtest/gtest.h>

#include <cstring>

using namespace overflight;

namespace {

struct Fallback {
    long long rows = 0;          // image rows not cast
    long long terrain_px = 0;    // of their pixels, terrain (depth < 1)
    long long differing_px = 0;  // of their pixels, not the marcher's color and depth bits
};

// Renders `cam` with the Floating Horizon and the ray marcher and compares
// the rows that TiltRows leaves out of the cast; checks the frame's counts.
Fallback compare_fallback_rows(const DataSet& ds, const Camera& cam, TiltMethod method, SurfaceModel surface) {
    FloatingHorizon fh(ds.terrain);
    const RayMarcher marcher(ds.terrain, ds.environment);
    RaycastOptions opt;
    opt.tilt = method;
    opt.surface = surface;
    ColorImage cf, cm;
    DepthImage df, dm;
    RaycastStats stats;
    fh.render(cam, ds.environment, opt, cf, df, &stats);
    marcher.render(cam, surface, cm, dm);
    TiltRows tilt;
    tilt_rows(cam, tilt);
    Fallback f;
    long long terrain_all = 0;
    for (int r = 0; r < cam.height; ++r) {
        const int j = cam.height - 1 - r; // bottom-up
        const bool cast = j >= tilt.j_lo && j < tilt.j_hi;
        f.rows += !cast;
        for (int c = 0; c < cam.width; ++c) {
            terrain_all += df.at(c, r) < 1.0f;
            if (cast) continue;
            f.terrain_px += df.at(c, r) < 1.0f;
            const bool same = cf.at(c, r) == cm.at(c, r) &&
                              std::memcmp(&df.at(c, r), &dm.at(c, r), sizeof(float)) == 0;
            f.differing_px += !same;
        }
    }
    EXPECT_EQ(stats.fallback_pixels, f.rows * cam.width);
    EXPECT_EQ(stats.pixels_painted, terrain_all);
    return f;
}

} // namespace

TEST(FloatingHorizonTilt, RowsPastTheVerticalGoToTheRayMarcher) {
    const DataSet ds = make_demo_island({257});
    for (TiltMethod method : {TiltMethod::Exact, TiltMethod::Guedes})
        for (SurfaceModel surface : {SurfaceModel::Blocks, SurfaceModel::Bilinear}) {
            // Looking 80 degrees down: the lower rows look back under the eye.
            const Camera cam = test::across_terrain(ds.terrain, 30, -80, Projection::Tilt);
            const Fallback f = compare_fallback_rows(ds, cam, method, surface);
            const char* what = method == TiltMethod::Exact ? "exact" : "guedes";
            EXPECT_GT(f.rows, 0) << what;
            EXPECT_LT(f.rows, cam.height) << what << ": some rows are cast";
            EXPECT_GT(f.terrain_px, 0) << what << ": the marcher's rows see the ground";
            EXPECT_EQ(f.differing_px, 0) << what;
        }
}

TEST(FloatingHorizonTilt, RowsNearTheZenithGoToTheRayMarcher) {
    const DataSet ds = make_demo_island({257});
    for (TiltMethod method : {TiltMethod::Exact, TiltMethod::Guedes}) {
        const Camera cam = test::across_terrain(ds.terrain, 200, 80, Projection::Tilt);
        const Fallback f = compare_fallback_rows(ds, cam, method, SurfaceModel::Blocks);
        EXPECT_GT(f.rows, 0);
        EXPECT_LT(f.rows, cam.height);
        EXPECT_EQ(f.differing_px, 0);
    }
}

// A level tilted camera casts every row: nothing falls back.
TEST(FloatingHorizonTilt, NoFallbackWhenEveryRowIsCast) {
    const DataSet ds = make_demo_island({257});
    const Camera cam = test::across_terrain(ds.terrain, 120, -20, Projection::Tilt);
    const Fallback f = compare_fallback_rows(ds, cam, TiltMethod::Exact, SurfaceModel::Blocks);
    EXPECT_EQ(f.rows, 0);
}
