// See FloatingHorizonTilt.h.
#include "raycast/FloatingHorizonTilt.h"

namespace overflight {

void prepare_tilt(FloatingHorizonState& s, const Camera& camera, const Environment& env,
                  const RaycastOptions& options, double fp_h) {
    const TiltRows& tr = s.tilt_rows;
    CastFrame& f = s.frame;
    s.prepare_slices(camera, options, camera.near * tr.w_min, camera.far * tr.w_max, fp_h);
    clip_columns(f.view, s.terrain.terrain, f.slices, f.columns);
    tilt_cast_rows(tr, f.rows);
    s.fog.build(env.fog_density, tilt_fog_reach(camera));
    if (s.imagery.bound()) {
        s.imagery.prepare_slices(f.slices.df.data(), int(f.slices.df.size()), fp_h);
        s.imagery.prepare_rows(f.rows.m.data(), f.rows.count);
    }
    const std::size_t columns = f.columns.a.size();
    s.tilt_color.resize(columns * std::size_t(f.rows.count));
    s.tilt_slice.resize(s.tilt_color.size());
    s.tilt_jend.resize(columns);
}

} // namespace overflight
