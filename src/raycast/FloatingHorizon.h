#pragma once
// The Floating Horizon terrain ray caster: color and OpenGL window depth of a
// height field + color map for the shared camera (DESIGN sec. 2), ready to be
// composited with Z-buffered objects.
//
// Based on: Szenberg, Gattass, Carvalho, "An Algorithm for the Visualization
// of a Terrain with Objects", SIBGRAPI 1997: Algorithm 1 (each pixel column is
// painted bottom-up, a sample that rises above the current horizon paints
// pixels until the horizon passes it), sec. 5.2 (slices parallel to the
// screen: column k steps by the unit step scaled by 1/cos(theta_k), so that
// slice i is at the same view depth d_i for every column and the horizon
// slope/height updates are shared by all columns), eq. 3-7 and Algorithm 2
// (depth vector), sec. 6 (depth stored with every painted pixel).
// Guedes, "Integrating Polygonal Objects on Voxel Based Terrain Models",
// Algorithm 1: per-row ray slopes dz[row] and incremental d-buffer for the
// pitched (`tilt`) camera.
//
// Exactness (no LaMothe/Freese approximations): every column's ray plane, the
// slice depths d_k = near + k*h_scale and the row slopes come from the camera
// contract; the horizon test "sample above the ray of row j at slice k" is
// done as (h - eye_y) / d_k > m_j, with 1/d_k tabulated per slice (shared by
// all columns, like the depth vector), so there is no division per sample.
// What remains is sampling: slices one cell apart point-sample the surface, so
// near the eye, where a cell spans several pixels, block fronts and corners
// can be missed; RaycastOptions::near_step_pixels narrows the slices there.
//
// Speed: columns are cast in blocks in parallel; the columns of a block take
// turns, a run of slices each, so that neighbours share terrain cache lines.
// Within a column, runs of slices that the max-height pyramid bounds below
// the current horizon are skipped (SliceRunBound: exact, they would paint
// nothing). Each block is cast into a per-thread scratch, row-major within
// the block, and resolved (fog, sky, depth: ShearResolve) into the row-major
// images, one run of pixels per image row; every per-frame table and scratch
// buffer is reused across frames (no allocation per frame once sizes are
// stable).
//
// The parts: FloatingHorizonTables (per-frame tables, pure functions),
// FloatingHorizonCast (the block cast, one build per instruction set),
// FloatingHorizonShear, FloatingHorizonTiltExact and FloatingHorizonTiltGuedes
// (one cast per camera model; both tilt casts share TiltResolve).
#include "core/Camera.h"
#include "core/DataSet.h"
#include "core/Image.h"
#include "core/SunLight.h"
#include "core/Terrain.h"
#include "raycast/RaycastOptions.h"

#include <memory>
#include <vector>

namespace overflight {

// Whether this build and CPU can run the block cast compiled for `kernel`.
bool cast_kernel_available(CastKernel kernel);

struct FloatingHorizonState;

class FloatingHorizon {
public:
    // Keeps a reference to terrain (it must outlive this object). Builds the
    // max-height pyramid for run skipping (a third of the height field's
    // size); the LOD pyramids are built on first use of --lod.
    explicit FloatingHorizon(const Terrain& terrain);
    ~FloatingHorizon();
    FloatingHorizon(const FloatingHorizon&) = delete;
    FloatingHorizon& operator=(const FloatingHorizon&) = delete;

    // Renders the terrain for `camera` (validated; throws Error("camera", ...))
    // with the fog and sky of `env` (their tables are rebuilt only when these
    // change). Resizes the images to the camera's size only when it differs.
    // Sky pixels get the sky gradient and depth 1.0; terrain pixels get the
    // fogged sample color and the window depth of their slice.
    // Shear cameras are exact (the papers' case). Tilt cameras use
    // options.tilt (see TiltMethod); rows whose rays point too steeply up or
    // down for vertical planes go to the ray marcher (stats->fallback_pixels).
    void render(const Camera& camera, const Environment& env, const RaycastOptions& options, ColorImage& color,
                DepthImage& depth, RaycastStats* stats = nullptr);

    // Paints `colors` (one per sample, e.g. sun-lit: core/SunLight.h; they
    // must outlive their use) from the next render on instead of the
    // terrain's own colors; null: the terrain's. Repacks them (linear in the
    // samples), so call it only when they change. With `mask`, the light
    // mask the colors were lit with (it must outlive its use too), a shadow
    // ends on a block's front face halfway between a shadowed and a lit
    // sample, as on the mesh (FrontFace.h), in every camera model.
    void set_colors(const std::vector<Rgb8>* colors, const LightMask& mask = {});
    // Imagery finer than the samples (null: none, the default): from the next
    // render on, the painted colors are taken as each sample's light (128 is
    // 1, core/SunLight.h LightOutput::Light) and multiplied by the imagery's
    // texel at the painted pixel's ground point on the mip level of its
    // footprint (ImageryTexels.h), for every camera model.
    void set_imagery(const ImageryPyramid* imagery);

private:
    std::unique_ptr<FloatingHorizonState> state_;
};

} // namespace overflight
