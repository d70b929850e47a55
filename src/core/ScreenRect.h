#pragma once
// The pixels a set of world boxes can cover on screen: the conservative
// rectangle around their projected corners. The compositor uses it to load the
// ray caster's depth only where objects can be depth-tested (Szenberg et al.
// 1997 sec. 5 and Table 1, "Z-buffer load", the step that bounds his frame
// rate): a fragment of an object lies inside the projection of its bounds, so
// outside the rectangle no depth value is ever read.
#include "core/Camera.h"

#include <glm/vec3.hpp>

#include <span>
#include <vector>

namespace overflight {

struct WorldBox {
    glm::vec3 lo, hi;
};

// Pixel rectangle, columns [col0, col1) and rows [row0, row1), row 0 at the top.
struct PixelRect {
    int col0 = 0, row0 = 0, col1 = 0, row1 = 0;
    bool empty() const { return col1 <= col0 || row1 <= row0; }
    long long area() const { return empty() ? 0 : (long long)(col1 - col0) * (row1 - row0); }
};

// The union of the screen rectangles of `boxes` for `camera`, one pixel wider
// on every side (rasterisation of lines and edges on the boundary), clipped to
// the image. A box wholly behind the near plane is skipped; of one cut by
// it, the part in front is bounded (its corners in front and its edges'
// crossings of the plane). No box in front gives an empty rectangle.
PixelRect screen_rect(std::span<const WorldBox> boxes, const Camera& camera);

// The smallest rectangle holding both (an empty one adds nothing).
PixelRect bounding_union(const PixelRect& a, const PixelRect& b);

// Pairwise disjoint rectangles whose union is exactly the union of `rects`
// (empty ones ignored): horizontal bands between the rectangles' row edges,
// each cut into the runs of columns some rectangle covers, and a band's
// runs merged with the band above where they are the same. A pass that
// blends into each pixel once (not idempotent) draws every one of them
// instead of the bounding rectangle of widely spread rects.
std::vector<PixelRect> disjoint_cover(std::span<const PixelRect> rects);

} // namespace overflight
