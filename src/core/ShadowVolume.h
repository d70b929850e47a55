#pragma once
// The shadow volume of a box: every point the box can shade from a sun at
// infinity, down to a floor, as a closed convex polyhedron (triangles wound
// counter-clockwise seen from outside). The compositor rasterises these
// volumes to mark the pixels whose terrain lies inside one (z-fail stencil
// counting), so that the objects' shadow pass shades those pixels alone
// instead of every pixel of the shadows' screen rectangles.
//
// The volume is the box swept along the sun's rays (the Minkowski sum of the
// box and the segment from 0 to -sun x L, L = (top - floor) / sun.y): the
// box's faces that look away from the sweep stay, those that look along it
// move to its end, and each edge between one of each (the silhouette seen
// along the sun) sweeps a parallelogram joining them. A face parallel to the
// sweep is counted with the faces that move, as if the sweep leaned an
// infinitesimal amount towards it, so the surface stays closed.
//
// Based on: F. Crow, "Shadow Algorithms for Computer Graphics" (SIGGRAPH
// 1977), the shadow volume of an occluder's silhouette; C. Everitt, M.
// Kilgard, "Practical and Robust Stenciled Shadow Volumes for
// Hardware-Accelerated Rendering" (NVIDIA 2002), sec. 3-4: closed volumes
// counted where they lie behind the scene (z-fail), with depth clamping.
#include "core/ScreenRect.h"

#include <glm/vec3.hpp>

#include <vector>

namespace overflight {

// Appends the shadow volume of `box` for the unit `sun` (towards the sun,
// sun.y > 0) down to `floor` to `triangles` (three points each): at most 24
// triangles. The volume holds every point p with p.y >= floor whose ray
// towards the sun meets the box. Nothing with sun.y <= 0.
void append_shadow_volume(const WorldBox& box, const glm::vec3& sun, float floor, std::vector<glm::vec3>& triangles);

} // namespace overflight
