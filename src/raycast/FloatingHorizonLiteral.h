#pragma once
// voxel-literal: Szenberg's Algorithm 1 transcribed as printed, single
// threaded, one column at a time, kept beside the fast FloatingHorizon as its
// reference and as the baseline of `overflight bench`.
//
// Based on: Szenberg, Gattass, Carvalho 1997, Algorithm 1 (CastRay), with the
// sec. 6 changes that make it comparable with OpenGL: [a] d_pk is the same for
// all columns (the focal length fp in pixels, since the screen is measured in
// pixels here), [b] the step (dx, dy) of column k has norm h_scale/cos(theta_k)
// (slices parallel to the screen, sec. 5.2), [c] every painted pixel stores
// Depth[i] (line 11A) from the depth vector of Algorithm 2. The first slice is
// at `near` and the last at `far`, as in sec. 5.1 [c]-[d]. Samples outside the
// terrain are skipped (the paper's map has no edge in view). Per painted pixel,
// fog and sky are computed exactly (std::exp, Atmosphere.h).
//
// Only the papers' camera is supported: projection `shear` (vertical view plane).
#include "core/Camera.h"
#include "core/DataSet.h"
#include "core/Image.h"
#include "core/ImageryPyramid.h"
#include "core/SunLight.h"
#include "core/Terrain.h"
#include "raycast/RaycastOptions.h"

#include <vector>

namespace overflight {

// Throws Error("projection", ...) for a tilt camera, Error("camera", ...) for a bad one.
// With `imagery` (finer than the samples), the painted colors are each
// sample's light (128 is 1) times the imagery's nearest texel at the slice's
// ground point on the mip level of the pixel's footprint (ImageryTexels.h).
// `colors` (one per sample, e.g. sun-lit: core/SunLight.h) are painted
// instead of the terrain's own when given. With `mask` (the light mask those
// colors were lit with), where it differs between the samples of slices i - 1
// and i, the rows whose rays pass below the point halfway between the two
// take sample i's color under sample i - 1's light (raycast/FrontFace.h).
void render_floating_horizon_literal(const Terrain& terrain, const Environment& env, const Camera& camera,
                                     SurfaceModel surface, ColorImage& color, DepthImage& depth,
                                     RaycastStats* stats = nullptr, const std::vector<Rgb8>* colors = nullptr,
                                     const ImageryPyramid* imagery = nullptr, const LightMask& mask = {});

} // namespace overflight
