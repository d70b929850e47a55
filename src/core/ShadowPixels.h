#pragma once
// The pixels of a depth image whose surface point may lie in the shadow of a
// box from the sun: what a screen-space shadow pass (gl/ShadowScreenPass.h)
// must cover, found per pixel on the CPU from the image's own depth, so that
// the pass shades the few pixels the shadows can darken instead of every
// pixel of each caster's screen rectangle (llvmpipe's cost is per pixel
// covered, the CPU's test is a few dozen flops).
//
// A point X lies in a box's shadow only if a ray from X towards the sun meets
// the box: seen along the sun (coordinates u, v across the sun, w along it),
// X's (u, v) falls inside the box's (u, v) extent and X's w is at most the
// box's highest w. The test is conservative in three ways, so that every
// pixel the pass would darken is kept:
// - the pass rebuilds X in float from the window depth (clip -> world, whose
//   w cancels towards the far plane: relative error about 2^-24 x
//   distance / near); the test grows the box by a margin of several times that;
// - the pass may move X along its ray onto the top of the terrain sample
//   nearest to it (the ray casters' slice offset): the test takes the whole
//   segment of the ray between X and each such top, for the samples that can
//   be nearest within the margin;
// - a ray too close to level for its direction to be sure keeps its pixel.
//
// Based on: L. Williams, "Casting Curved Shadows on Curved Surfaces"
// (SIGGRAPH 1978): a point is shadowed iff the light's view sees something
// nearer along its ray; here, bounding that something by the casters' boxes.
#include "core/Camera.h"
#include "core/Image.h"
#include "core/ScreenRect.h"
#include "core/Terrain.h"

#include <glm/vec3.hpp>

#include <span>
#include <vector>

namespace overflight {

class HeightBounds;

// The grid of terrain samples the pass snaps its points to: every `stride`-th
// sample of `terrain` in each direction, `texels_per_unit` of them per world
// unit as the pass computes it (float). `bounds`: HeightBounds(*terrain,
// stride) kept by the caller across frames; null: built by each call.
struct SnapGrid {
    const Terrain* terrain = nullptr;
    int stride = 1;
    float texels_per_unit = 1.0f;
    const HeightBounds* bounds = nullptr;
};

// What casts a shadow: the convex hull of `points` grown by `margin` every way.
struct ShadowCaster {
    std::span<const glm::vec3> points;
    float margin = 0;
};

// Pairwise disjoint rectangles covering every pixel of `depth` (for
// `camera`, window depth, 1 = sky) that lies inside rects[i] and whose point
// may be in the shadow of casters[i] from the unit direction `sun` (towards
// the sun, y > 0), for some i. rects and casters have the same length. A
// caster is bounded, seen along the sun, by two rectangles: one along the
// sun's frame, one along the line from its first point to its last (a run
// of cable crossing the view diagonally). Each row's runs of such pixels,
// merged with the rows below while they are the same. No GL: any thread.
//
// Cost: the per-pixel test runs only in tiles of 8 x 8 pixels that some
// caster may shadow, judged from the tile's nearest and farthest depth and
// the lowest and highest sample top near it (the hull of every point its
// pixels may test); the other tiles cost a read of their depths.
// `per_tile` false: every pixel in the rectangles is tested (the same
// result, for tests of the tiles' rejection).
std::vector<PixelRect> shadow_pixels(const DepthImage& depth, const Camera& camera, const SnapGrid& grid,
                                     const glm::vec3& sun, std::span<const ShadowCaster> casters,
                                     std::span<const PixelRect> rects, bool per_tile = true);

} // namespace overflight
