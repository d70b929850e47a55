#pragma once
// The water surface (core/WaterSurface.h) in the ray casters' images: one
// pass over the color and window-depth images a ray caster (voxel,
// voxel-literal, raymarch; shear or tilt camera) made of the dry terrain.
//
// The surface the caster should have seen is max(terrain, level): along a
// pixel's ray that is the water plane wherever the ray meets the plane before
// the terrain (or the sky), i.e. wherever the plane's window depth at the
// pixel is smaller than the image's. Those pixels get the plane's exact depth
// (OpenGL convention, so objects composite against the water as against the
// terrain) and the water's color:
//   - the mirrored ray (the view ray reflected at the waves' normal) is
//     marched through the same height field as the reference ray marcher
//     does (RayMarcher::intersect, exact for the `blocks` surface, a quarter
//     cell for `bilinear`) up to where it rises above the highest sample: the
//     reflected color is the lit sample it hits, fogged over the mirrored
//     path (GL_EXP; with the atmosphere, its aerial perspective from the
//     water point), or the sky along it. The only error is the surface
//     model's own: no approximation of the march;
//   - the bottom is what the image held at that pixel (the terrain under the
//     water, fogged), the water path from the depth under the point
//     (water_path of the bilinear surface);
//   - water_light, fogged from the eye like any terrain, over the bottom.
// The eye below the level sees the water from under it (core/WaterSurface.h):
// the surface from below where a rising ray meets the plane before the
// terrain (the plane's depth), and everything else dimmed by the water's
// extinction over its path under the level.
// Pixels elsewhere are not touched: without water the images are the caster's.
//
// Cost: one unprojection per pixel, and per water pixel one march of the
// mirrored ray. The mirrored ray rises, so for the `blocks` surface the march
// jumps over every block of the terrain's max-height pyramid it passes above
// (RayMarcher::set_pyramid: the same hits as the plain cell march, bit for
// bit) and ends once it is above the whole terrain (the pyramid's top).
#include "core/Camera.h"
#include "core/DataSet.h"
#include "core/Image.h"
#include "core/SunLight.h"
#include "core/Terrain.h"
#include "raycast/HeightPyramid.h"
#include "raycast/RaycastOptions.h"

#include <vector>

namespace overflight {

class WaterPass {
public:
    // Keeps a reference to terrain (it must outlive this object) and builds
    // its max-height pyramid (the terrain's heights must not change after).
    // `sun_shadow` (may be null; must outlive this object): the sweep the
    // lighting over imagery shares with the caster's (TerrainLighting).
    explicit WaterPass(const Terrain& terrain, SharedSunShadow* sun_shadow = nullptr);
    // The sample colors the reflections and the bottom show: `colors` as the
    // caster paints them (sun-lit; null: the terrain's; must outlive their
    // use), except over imagery finer than the samples, whose caster paints
    // light alone: then the terrain's own colors (the imagery averaged per
    // sample) lit for `env` here.
    void set_colors(const std::vector<Rgb8>* colors, const Environment& env);
    // Off: the mirrored rays march every cell (the plain reference march the
    // pyramid's skipping reproduces); on (the default): they skip.
    void set_skipping(bool on) { skipping_ = on; }

    // Floods `color`/`depth` (the caster's images for `camera`, its size)
    // to env.water_level when env.water is on; returns the water pixels
    // (with the eye under the level, those of the surface seen from below).
    long long apply(const Camera& camera, const Environment& env, SurfaceModel surface, ColorImage& color,
                    DepthImage& depth) const;

private:
    long long apply_under(const Camera& camera, const Environment& env, SurfaceModel surface, ColorImage& color,
                          DepthImage& depth) const;

    const Terrain& terrain_;
    const double top_; // Terrain::max_height(), which reads every sample
    const std::vector<Rgb8>* colors_ = nullptr;
    TerrainLighting albedo_lighting_; // used over imagery only
    HeightPyramid pyramid_;
    bool skipping_ = true;
};

} // namespace overflight
