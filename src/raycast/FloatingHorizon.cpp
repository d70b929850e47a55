// Based on: Szenberg, Gattass, Carvalho, "An Algorithm for the Visualization
// of a Terrain with Objects", SIBGRAPI 1997, sec. 5.2 (the slices) and
// Algorithm 2 (depth vector). See FloatingHorizon.h.
#include "raycast/FloatingHorizon.h"

#include "raycast/FloatingHorizonState.h"

namespace overflight {

FloatingHorizon::FloatingHorizon(const Terrain& terrain) : state_(std::make_unique<FloatingHorizonState>(terrain)) {}

FloatingHorizon::~FloatingHorizon() = default;

void FloatingHorizon::set_colors(const std::vector<Rgb8>* colors, const LightMask& mask) {
    state_->terrain.set_colors(colors, mask);
}

void FloatingHorizon::set_imagery(const ImageryPyramid* imagery) { state_->imagery.bind(imagery); }

void FloatingHorizon::render(const Camera& camera, const Environment& env, const RaycastOptions& options,
                             ColorImage& color, DepthImage& depth, RaycastStats* stats) {
    const auto t0 = Clock::now();
    camera.validate();
    if (color.width != camera.width || color.height != camera.height) color.resize(camera.width, camera.height);
    if (depth.width != camera.width || depth.height != camera.height) depth.resize(camera.width, camera.height);
    FloatingHorizonState& s = *state_;
    s.frame.view = view_axes(camera, s.terrain.terrain.h_scale());
    s.sky.build(env);
    s.fog_color = pack_rgb(to_rgb8(env.fog_color));
    s.air_on = env.atmosphere;
    if (s.air_on) {
        const AerialFrame air = aerial_frame(env, camera.eye.y);
        s.air.build(air, float(s.terrain.min_height - camera.eye.y), float(s.terrain.max_height - camera.eye.y));
        s.sun = air.sun;
    }
    RaycastStats local;
    if (camera.projection == Projection::Shear) cast_shear(s, camera, env, options, color, depth, local);
    else if (options.tilt == TiltMethod::Exact) cast_tilt_exact(s, camera, env, options, color, depth, local);
    else cast_tilt_guedes(s, camera, env, options, color, depth, local);
    local.slices = int(s.frame.slices.d.size());
    local.samples = (long long)local.columns * (long long)local.slices;
    local.ms_total = ms_since(t0);
    if (stats) *stats = local;
}

void FloatingHorizonState::prepare_slices(const Camera& camera, const RaycastOptions& options, double d_first,
                                          double d_last, double fp_h) {
    const Terrain& t = terrain.terrain;
    SlicePlacement placement;
    placement.d_first = d_first;
    placement.d_last = d_last;
    placement.h_scale = t.h_scale();
    placement.fp_h = fp_h;
    placement.lod = options.lod;
    placement.lod_levels = options.lod ? terrain.lod_levels() : 0;
    placement.lod_pixels = options.lod_pixels;
    placement.near_step_pixels = options.near_step_pixels;
    place_slices(placement, frame.slices);
    slice_slopes(frame.slices.d, t, terrain.max_height, frame.view.eye_y, frame.slopes);
    // The bound reads the raw maximum as the highest world point: v_scale > 0.
    frame.skip_runs = options.skip_runs && t.v_scale() > 0.0f;
    // Shear: the view axis is F, so slice k's window depth is one number for
    // the whole slice (Algorithm 2). Tilt resolves depth per pixel instead.
    if (camera.projection == Projection::Shear) slice_window_depths(camera, frame.slices, slice_depth);
}

} // namespace overflight
