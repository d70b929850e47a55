// The affine transform between world X, Z and a grid's map coordinates
// (core/GridGeoreference.h), with hand-computed literals.
#include "core/GridGeoreference.h"

#include <gtest/gtest.h>

namespace overflight {
namespace {

TEST(GridGeoreference, NorthUpGrid) {
    // 30 m pixels, top-left corner of pixel (0, 0) at (500000, 5200000).
    const GridGeoreference g({500000.0, 30.0, 0.0, 5200000.0, 0.0, -30.0}, 30.0);
    // Sample (0, 0) stands at its pixel's centre.
    EXPECT_EQ(g.map_of_world(0, 0), glm::dvec2(500015.0, 5199985.0));
    // Sample (row 2, col 3): X = 90, Z = 60.
    EXPECT_EQ(g.map_of_world(90, 60), glm::dvec2(500105.0, 5199925.0));
    EXPECT_EQ(g.world_of_map(500105.0, 5199925.0), glm::dvec2(90.0, 60.0));
    EXPECT_EQ(g.world_of_map(500000.0, 5200000.0), glm::dvec2(-15.0, -15.0));
}

TEST(GridGeoreference, RotatedGridRoundTrips) {
    const GridGeoreference g({1000.0, 8.0, 6.0, 2000.0, 6.0, -8.0}, 10.0);
    // Pixel (col 0.5, row 0.5): 1000 + 4 + 3, 2000 + 3 - 4.
    EXPECT_EQ(g.map_of_world(0, 0), glm::dvec2(1007.0, 1999.0));
    const glm::dvec2 w = g.world_of_map(1234.5, 1876.25);
    const glm::dvec2 m = g.map_of_world(w.x, w.y);
    EXPECT_NEAR(m.x, 1234.5, 1e-9);
    EXPECT_NEAR(m.y, 1876.25, 1e-9);
}

} // namespace
} // namespace overflight
