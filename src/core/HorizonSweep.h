#pragma once
// The terrain's cast shadows for one sun direction, as a per-sample shadow
// ceiling: the world height below which a point above sample (row, col) sees
// the terrain between itself and the sun. A sample is in the terrain's shadow
// iff its own height is below its ceiling; any other point at the same (X, Z),
// an object's fragment for instance, iff its height is.
//
// Based on: A. J. Stewart, "Fast Horizon Computation at All Points of a
// Terrain with Visibility and Shading Applications" (IEEE TVCG 1998), sec. 1
// and 3: the horizon of every sample in one direction is found by sweeping
// the grid in that direction rather than by one ray per sample. For a single
// sun elevation e the horizon reduces to a running maximum: a point p is in
// the shadow iff some terrain point q up-sun, s away horizontally, has
// h(q) - s tan(e) > y(p).
//
// The sweep follows sun lines: straight lines along the sun's azimuth, one
// per sample spacing, crossing the grid lines (columns or rows, whichever
// the azimuth crosses more often) one after the other, away from the sun.
// Where a sun line crosses a grid line the terrain's height is exact (the
// height field is linear along a grid line between two samples, for the
// mesh and bilinear surfaces alike), so each sun line carries the exact
// ceiling of the points on it:
//     ceiling(next crossing) = max(h(crossing), ceiling(crossing)) - rise.
// A sample between two sun lines gets their two ceilings interpolated
// linearly; being interpolated once and never carried on, that error stays
// within the one cell between them and does not spread down the shadow.
//
// Speed: one pass over the grid; the sun lines are independent, swept in
// narrow bands in parallel (oneTBB), each band sweeping one sun line of the
// next. A band keeps what it touches of a grid line in the first-level cache
// and reads each grid line's heights once into a contiguous buffer, so that
// its inner loops vectorize whichever axis the sun lines cross (compiled for
// AVX2 and AVX-512 as well and picked at run time; no FMA, so the same bits).
#include "core/Terrain.h"

#include <glm/vec3.hpp>

#include <cstdint>
#include <vector>

namespace overflight {

struct ShadowCeiling {
    // No terrain between the point and the sun (the map's edge up-sun, or a
    // sun in the zenith): far below any world height (kWorldLimit), finite so
    // that interpolating it stays finite.
    static constexpr float kOpen = -1e30f;

    int rows = 0, cols = 0;
    glm::vec3 sun_dir{0.0f}; // what it was computed for (unit)
    std::vector<float> ceiling; // world heights, row-major rows x cols

    float at(int row, int col) const { return ceiling[std::size_t(row) * std::size_t(cols) + std::size_t(col)]; }
    // Whether a point at world height y above sample (row, col) is in the terrain's shadow.
    bool shadowed(int row, int col, float y) const { return y < at(row, col); }
};

// Computes `out` for the sun direction `sun_dir` (towards the sun, world
// space, any length > 0). A sun at or below the horizon (sun_dir.y <= 0)
// shadows everything: every ceiling is +infinity. Reuses out's storage.
void sweep_shadow_ceiling(const Terrain& terrain, const glm::vec3& sun_dir, ShadowCeiling& out);

// The per-sample mask alone (1 = in the terrain's shadow), row-major: the
// same as shadow_mask(terrain, ceiling) for the ceiling sweep_shadow_ceiling
// computes, written by the sweep as it goes (a byte per sample rather than a
// float ceiling through memory and back: what the sun's light on the samples
// needs, SunLight.h). A sun at or below the horizon shadows everything.
// Reuses mask's storage.
void sweep_shadow_mask(const Terrain& terrain, const glm::vec3& sun_dir, std::vector<std::uint8_t>& mask);

// Both in one pass: the ceiling (as sweep_shadow_ceiling) and its mask (as
// sweep_shadow_mask), for a renderer whose objects read the one and whose
// terrain samples the other (a ray caster composited with objects), at
// 1.1-1.3 times the cost of the ceiling alone rather than 1.5-2 times for
// the two sweeps (README, sun shadows). Reuses the storage of both.
void sweep_shadow(const Terrain& terrain, const glm::vec3& sun_dir, ShadowCeiling& ceiling,
                  std::vector<std::uint8_t>& mask);

// Per-sample mask (1 = in the terrain's shadow) of a sample's own height
// against its ceiling, row-major.
std::vector<std::uint8_t> shadow_mask(const Terrain& terrain, const ShadowCeiling& ceiling);

} // namespace overflight
