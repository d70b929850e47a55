#pragma once
// Where an orthophoto does not cover the terrain (outside the source raster,
// on its no-data) the terrain keeps the colors it would have without one
// (Shading.h: elevation ramp x hillshade), blended into the imagery over a
// few texels at the coverage's edge, so no picture shows a black band or a
// hard seam. Done once on the pyramid's level 0, so every method that samples
// the imagery (the ray casters per sample, the GL methods per fragment) shows
// the same fallback.
#include "core/ImageryPyramid.h"
#include "core/Terrain.h"

namespace overflight {

// Texels over which the imagery fades into the fallback colors inside its coverage.
inline constexpr int kImageryFeatherTexels = 3;

// Rewrites the colors of level 0 as imagery x w + fallback x (1 - w), the
// fallback the terrain's color bilinear at the texel's centre (clamped to the
// terrain), w = min(alpha, mean alpha over the (2 feather + 1)^2 texels
// around it) / 255: 0 outside the coverage, rising to 1 `feather` texels
// inside it. Alphas are kept (they still say what the source covered);
// levels 1.. are rebuilt. `terrain` holds the fallback colors.
void blend_over_terrain_colors(ImageryPyramid& imagery, const Terrain& terrain,
                               int feather = kImageryFeatherTexels);

// Sets each terrain sample's color to the imagery around it: bilinear at the
// sample's world position on the level whose texels are the size of a
// terrain cell (mip_level_for_footprint of h_scale), for the renderers and
// distances that draw one color per sample.
void colors_from_imagery(const ImageryPyramid& imagery, Terrain& terrain);

} // namespace overflight
