#pragma once
// What the Floating Horizon keeps across frames (private to src/raycast):
// the terrain as the cast samples it, the frame's tables and the scratch
// buffers, all reused so that a frame allocates nothing once sizes are stable;
// and the three casts that fill them, one per camera model.
#include "core/Camera.h"
#include "core/DataSet.h"
#include "core/HugePages.h"
#include "core/Image.h"
#include "core/Parallel.h"
#include "raycast/Atmosphere.h"
#include "raycast/FloatingHorizonCast.h"
#include "raycast/FloatingHorizonTables.h"
#include "raycast/ImageryTexels.h"
#include "raycast/RaycastOptions.h"

#include <chrono>
#include <cstdint>
#include <vector>

namespace overflight {

struct FloatingHorizonState {
    explicit FloatingHorizonState(const Terrain& t) : terrain(t) {}

    // The frame's slices from d_first to d_last along F (fp_h: the cast's
    // focal length in pixels, for the LOD and near steps) and the per-slice
    // tables derived from them; frame.view must be set.
    void prepare_slices(const Camera& camera, const RaycastOptions& options, double d_first, double d_last,
                        double fp_h);

    CastTerrain terrain;
    CastFrame frame;
    std::vector<float> slice_depth; // shear: window depth of slice k (eq. 7)
    SkyTable sky;
    FogTable fog;
    std::uint32_t fog_color = 0; // packed
    // Environment::atmosphere: the aerial perspective's tables (built by
    // render) and the frame's sun direction; fog and sky above are unused.
    bool air_on = false;
    AerialTables air;
    glm::dvec3 sun{0.0, 1.0, 0.0};
    // Imagery finer than the samples (FloatingHorizon::set_imagery): the
    // cast paints light, the imagery's texel at each painted pixel's ground
    // point multiplies it.
    ImageryTexels imagery;

    // A terrain hit's packed color seen from the eye (distance, height above
    // the eye, cosine to the sun of the ray): through the air or fogged.
    std::uint32_t hit_color(std::uint32_t color, float distance, float dy, float cos_sun) const {
        return air_on ? air.terrain(color, distance, dy, cos_sun) : fog_blend(color, fog_color, fog.weight(distance));
    }
    // The sky along a ray of elevation sine `sine` and cosine to the sun `cos_sun`.
    std::uint32_t sky_color(float sine, float cos_sun) const {
        return air_on ? air.sky(sine, cos_sun) : sky.color(sine);
    }

    // Shear: one block's cast, row-major within the block, per thread, on
    // huge pages (HugePages.h: at 4K the block spans 136 pages of 4 KiB).
    struct BlockScratch {
        // The block's colors, then its slices (kShearBlock x (H + kPaintRows)
        // each): one allocation, so that both share one 2 MiB page up to 8K.
        std::vector<std::uint32_t, HugePageAllocator<std::uint32_t>> pixels;
        std::vector<int> jend;
    };
    parallel::ThreadLocal<BlockScratch> block_scratch;
    // Shear: the blocks go right to left in every other frame, so that a
    // frame's first blocks write image lines that the previous frame wrote
    // last, which the last-level cache may still hold (the 58 MB of a 4K
    // frame's color and depth do not fit in it whole).
    bool blocks_backwards = false;

    // Tilt: the whole image's cast, column-major (one cast column after the other).
    TiltRows tilt_rows;
    std::vector<std::uint32_t> tilt_color, tilt_slice;
    std::vector<int> tilt_jend;
};

// The casts, one per camera model (FloatingHorizon::render picks): each
// fills the images and the stats' setup, cast and resolve steps.
void cast_shear(FloatingHorizonState& s, const Camera& camera, const Environment& env, const RaycastOptions& options,
                ColorImage& color, DepthImage& depth, RaycastStats& stats);
void cast_tilt_exact(FloatingHorizonState& s, const Camera& camera, const Environment& env,
                     const RaycastOptions& options, ColorImage& color, DepthImage& depth, RaycastStats& stats);
void cast_tilt_guedes(FloatingHorizonState& s, const Camera& camera, const Environment& env,
                      const RaycastOptions& options, ColorImage& color, DepthImage& depth, RaycastStats& stats);

using Clock = std::chrono::steady_clock;
inline double ms_since(Clock::time_point t0) {
    return std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
}

} // namespace overflight
