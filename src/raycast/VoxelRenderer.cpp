// The voxel method's frame: light, cast, water. See VoxelRenderer.h.
#include "raycast/VoxelRenderer.h"

#include <chrono>

namespace overflight {

namespace {

double ms_since(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

} // namespace

VoxelRenderer::VoxelRenderer(const Terrain& terrain, const RaycastOptions& options, SharedSunShadow* sun_shadow)
    : caster_(terrain), lighting_(terrain, terrain.imagery() ? LightOutput::Light : LightOutput::Colors, sun_shadow),
      water_(terrain, sun_shadow), options_(options) {
    // Imagery finer than the samples: the cast paints light, the imagery the albedo.
    caster_.set_imagery(terrain.imagery());
}

void VoxelRenderer::render(const Camera& camera, const Environment& env, ColorImage& color, DepthImage& depth,
                           VoxelFrameStats& stats) {
    stats = {};
    const auto t0 = std::chrono::steady_clock::now();
    const std::vector<Rgb8>* colors = lighting_.colors(env);
    if (lighting_.version() != painted_) {
        caster_.set_colors(colors, lighting_.light_mask());
        painted_ = lighting_.version();
        stats.relit = true;
        stats.light_ms = ms_since(t0);
    }
    caster_.render(camera, env, options_, color, depth, &stats.raycast);
    if (env.water) {
        const auto tw = std::chrono::steady_clock::now();
        water_.set_colors(colors, env);
        water_.apply(camera, env, options_.surface, color, depth);
        stats.water = true;
        stats.water_ms = ms_since(tw);
    }
}

} // namespace overflight
