// The distance LOD's silhouette measure (raycast/LodAccuracy.h) on literal
// depth images, and on the ray caster itself: the exact cast agrees with
// itself everywhere, and a coarser LOD moves a small island's outline further.
#include "core/DemoIsland.h"
#include "core/Error.h"
#include "raycast/FloatingHorizon.h"
#include "raycast/LodAccuracy.h"

#include <gtest/gtest.h>


using namespace overflight;

namespace {

// A 4x5 depth image from rows of characters: '.' sky, '#' terrain (row 0 = top).
DepthImage literal(const char* const (&rows)[5]) {
    DepthImage img(4, 5, 1.0f);
    for (int row = 0; row < 5; ++row)
        for (int col = 0; col < 4; ++col)
            if (rows[row][col] == '#') img.at(col, row) = 0.5f;
    return img;
}

} // namespace

TEST(LodAccuracy, LiteralColumns) {
    const DepthImage reference = literal({"....", //
                                          "#...", //
                                          "##..", //
                                          "###.", //
                                          "###."});
    // Column 0 one row higher (within), column 1 two rows higher (not),
    // column 2 the same, column 3 terrain where the reference is all sky (not).
    const DepthImage test = literal({"##..", //
                                     "##..", //
                                     "##..", //
                                     "###.", //
                                     "####"});
    const SilhouetteAgreement a = compare_silhouettes(test, reference);
    EXPECT_EQ(a.pixels, 20);
    EXPECT_EQ(a.sky_agreeing, 20 - 4); // (0,0), (1,0), (1,1), (3,4)
    EXPECT_EQ(a.columns, 4);
    EXPECT_EQ(a.columns_within, 2);
    EXPECT_EQ(a.max_row_difference, 2);
    EXPECT_DOUBLE_EQ(a.sky_share(), 0.8);
    EXPECT_DOUBLE_EQ(a.column_share(), 0.5);
    // A looser tolerance takes column 1 in; column 3 stays out (sky in one only).
    EXPECT_EQ(compare_silhouettes(test, reference, 2).columns_within, 3);
    // Sky in both columns agrees.
    const DepthImage sky(4, 5, 1.0f);
    EXPECT_EQ(compare_silhouettes(sky, sky).columns_within, 4);
}

TEST(LodAccuracy, RejectsMismatchedImages) {
    EXPECT_THROW(compare_silhouettes(DepthImage(4, 5, 1.0f), DepthImage(5, 4, 1.0f)), Error);
    EXPECT_THROW(compare_silhouettes(DepthImage(4, 5, 1.0f), DepthImage(4, 5, 1.0f), -1), Error);
}

TEST(LodAccuracy, CoarserLodMovesTheOutline) {
    DemoOptions demo;
    demo.size = 257;
    const DataSet data = make_demo_island(demo);
    const Terrain& t = data.terrain;
    Camera cam;
    cam.width = 320;
    cam.height = 180;
    cam.fov = 60;
    cam.pitch = -4;
    cam.heading = 180;
    cam.near = 1;
    cam.far = 4.0 * t.width();
    cam.eye = {0.5 * t.width(), double(t.max_height()) + 20.0 * t.h_scale(), double(t.depth()) * 1.02};
    FloatingHorizon fh(t);
    ColorImage color;
    DepthImage exact, lod;
    RaycastOptions options;
    fh.render(cam, data.environment, options, color, exact);
    const SilhouetteAgreement self = compare_silhouettes(exact, exact);
    EXPECT_EQ(self.sky_agreeing, self.pixels);
    EXPECT_EQ(self.columns_within, self.columns);
    // The LOD starts where a pixel spans lod_pixels * 2 cells: at 0.5 beyond
    // this island (the exact outline), at 0.1 from about 55 cells on, where
    // the max-height pyramid raises the distant ridges by many rows. The
    // finer the LOD, the closer the outline.
    options.lod = true;
    double last_columns = 0.0, last_sky = 0.0;
    for (const double px : {0.1, 0.2, 0.5}) {
        options.lod_pixels = px;
        fh.render(cam, data.environment, options, color, lod);
        const SilhouetteAgreement a = compare_silhouettes(lod, exact);
        EXPECT_GE(a.column_share(), last_columns) << px;
        EXPECT_GE(a.sky_share(), last_sky) << px;
        last_columns = a.column_share();
        last_sky = a.sky_share();
        if (px == 0.1) {
            EXPECT_LT(a.column_share(), 0.9);
            EXPECT_GT(a.max_row_difference, 10);
        }
    }
    EXPECT_GT(last_sky, 0.999);
    EXPECT_GT(last_columns, 0.98);
}
