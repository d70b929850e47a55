#pragma once
// Where the light changes on a front face of the Floating Horizon (private to
// src/raycast). Algorithm 1 of Szenberg, Gattass, Carvalho, "An Algorithm for
// the Visualization of a Terrain with Objects", SIBGRAPI 1997, paints with
// sample k the rows from the horizon its nearer samples left up to its own
// top: the vertical span between the near sample's top and the far sample's
// top (the block's front face, and on level ground the ground between the two
// slices). The mesh shows there the slope between the two samples, whose
// shadow test is the nearest sample's (gl/GlProgram.cpp, sun_visible): the
// near half of the slope takes the near sample's light state, the far half
// the far sample's. Painted with the far sample's state alone, a shadow's
// edge sat up to a cell nearer the eye than the mesh's (on the demo island's
// cliffs, seen from 1500 above, the shadow masks' IoU was 0.80).
//
// So where the light mask (core/SunLight.h, LightMask) differs between
// samples k - 1 and k, the rows of sample k's span below the point where the
// mesh's shadow changes get sample k's color under sample k - 1's light state
// (LightMask::other_colors); the rows above it, sample k's own. That point is
// where the column's ray passes from sample k - 1's cell (the ground nearest
// to it) into the cells in sample k's state (cell_crossing), at the height
// of the slope there: halfway between the two samples' heights on the blocks
// surface (the cells meet halfway between the samples), interpolated along
// the ray on the bilinear one. Only the light moves: a block keeps its own albedo and
// normal, so the unshadowed and the baked pictures are unchanged. Sample
// k - 1 is the previous slice's sample along the column whether it painted or
// not (the slope's near half may show above a hidden sample); the first slice
// of a column, and the distance LOD's coarse levels (which have no mask),
// change nothing.
#include "raycast/FloatingHorizonTables.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

namespace overflight {

// The cast's packed sample colors (CastTerrain::colors, 0x00BBGGRR) carry the
// light mask in their top byte: kShadowedBit where the sample is shadowed.
// Every color painted is masked with kRgbBits.
constexpr std::uint32_t kShadowedBit = 1u << 24;
constexpr std::uint32_t kRgbBits = 0x00FFFFFFu;

// Whether samples of packed words `near` and `far` differ in light state.
inline bool light_changes(std::uint32_t near, std::uint32_t far) { return ((near ^ far) & kShadowedBit) != 0; }

// The fraction in [0, 1] of the step from (x0, z0) to (x1, z1) (grid units
// offset by half a cell, so that sample (row, col)'s cell is [col, col + 1) x
// [row, row + 1)) at which the light changes from the near sample's state
// `near_shadowed` to the far one's: where the ray leaves the near cell, or
// enters the far one where the step cuts through a third cell at a corner
// (leaves, if that cell is in the far sample's state: shadowed_at(col, row)
// tells); 0.5 if both are the same cell.
template <class ShadowedAt>
double cell_crossing(double x0, double z0, double x1, double z1, bool near_shadowed, const ShadowedAt& shadowed_at) {
    double leave = 1.0, enter = 0.0, tx = -1.0, tz = -1.0;
    const auto axis = [&](double p0, double p1, double& t_first) {
        const double c0 = std::floor(p0), c1 = std::floor(p1);
        if (c0 == c1) return;
        const double first = p1 > p0 ? c0 + 1.0 : c0, last = p1 > p0 ? c1 : c1 + 1.0;
        t_first = (first - p0) / (p1 - p0);
        leave = std::min(leave, t_first);
        enter = std::max(enter, (last - p0) / (p1 - p0));
    };
    axis(x0, x1, tx);
    axis(z0, z1, tz);
    if (tx < 0.0 && tz < 0.0) return 0.5;
    if (tx < 0.0 || tz < 0.0) return 0.5 * (leave + enter); // one axis: one grid line (or two, a long step)
    // A corner: the cell between is the near one moved along the axis crossed first.
    const bool x_first = tx < tz;
    const int col = int(std::floor(x_first ? x1 : x0)), row = int(std::floor(x_first ? z0 : z1));
    return shadowed_at(col, row) == near_shadowed ? enter : leave;
}

// The slope (per unit of view depth, as SliceSlopes) of the point where the
// light changes between the samples of slices at view depths d_near and d_far
// of heights h_near and h_far (raw units), the ray crossing cells at fraction
// t of the step: rows of smaller slope are below it.
inline float change_slope(const SliceSlopes& s, double d_near, double d_far, double t, double h_near, double h_far,
                          bool bilinear) {
    const double h = bilinear ? h_near + t * (h_far - h_near) : 0.5 * (h_near + h_far);
    return float((s.v_scale * h + s.base) / (d_near + t * (d_far - d_near)));
}

} // namespace overflight
