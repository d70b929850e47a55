#pragma once
// The Floating Horizon terrain ray caster: color and OpenGL window depth of a
// height field + color map for the shared camera (DESIGN sec. 2), ready to be
// composited with Z-buffered objects.
//
// Based on: Szenberg, Gattass, Carvalho 1997 (seed 000): Algorithm 1 (each
// pixel column is painted bottom-up, a sample that rises above the current
// horizon paints pixels until the horizon passes it), sec. 5.2 (slices parallel
// to the screen: column k steps by the unit step scaled by 1/cos(theta_k), so
// that slice i is at the same view depth d_i for every column and the horizon
// slope/height updates are shared by all columns), eq. 3-7 and Algorithm 2
// (depth vector), sec. 6 (depth stored with every painted pixel).
// Guedes (seed 002), Algorithm 1: per-row ray slopes dz[row] and incremental
// d-buffer for the pitched (`tilt`) camera.
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
// Speed: columns are cast in blocks in parallel (oneTBB); the columns of a
// block take turns, a run of slices each, so that neighbours share terrain
// cache lines. Within a column, runs of slices that the max-height pyramid
// bounds below the current horizon are skipped (SliceRunBound: exact, they
// would paint nothing). Each block is
// cast into a per-thread scratch, row-major within the block, and resolved
// (fog, sky, depth: ShearResolve) into the row-major images, one run of pixels
// per image row; every per-frame table and scratch buffer is reused across
// frames (no allocation per frame once sizes are stable).
#include "core/Camera.h"
#include "core/DataSet.h"
#include "core/Image.h"
#include "core/Terrain.h"
#include "raycast/Atmosphere.h"
#include "raycast/HeightPyramid.h"
#include "raycast/RayMarcher.h"
#include "raycast/RaycastOptions.h"

#include <tbb/enumerable_thread_specific.h>

#include <cstdint>
#include <memory>
#include <vector>

namespace overflight {

// Whether this build and CPU can run the block cast compiled for `kernel`.
bool cast_kernel_available(CastKernel kernel);

class FloatingHorizon {
public:
    // Keeps references to terrain and env (they must outlive this object).
    // Builds the max-height pyramid for run skipping (a third of the height
    // field's size); the LOD pyramids are built on first use of --lod.
    FloatingHorizon(const Terrain& terrain, const Environment& env);
    ~FloatingHorizon();

    // Renders the terrain for `camera` (validated; throws Error("camera", ...)).
    // Resizes the images to the camera's size only when it differs. Sky pixels
    // get the sky gradient and depth 1.0; terrain pixels get the fogged sample
    // color and the window depth of their slice.
    // Shear cameras are exact (the papers' case). Tilt cameras use
    // options.tilt (see TiltMethod).
    void render(const Camera& camera, const RaycastOptions& options, ColorImage& color, DepthImage& depth,
                RaycastStats* stats = nullptr);

private:
    struct TiltRows {
        std::vector<double> w, m; // per image row r (top-down): F component and slope of the row's rays
        int j_lo = 0, j_hi = 0;   // rows cast, bottom-up index range [j_lo, j_hi); the rest go to the ray marcher
        double w_min = 1, w_max = 1;
    };
    const TiltRows& tilt_rows(const Camera& camera); // fills tilt_rows_
    void setup_slices(const Camera& camera, const RaycastOptions& options, double d_first, double d_last, double fp_h);
    void setup_columns(); // from col_a_
    void cast_shear(const Camera& camera, const RaycastOptions& options, ColorImage& color, DepthImage& depth,
                    RaycastStats& stats);
    void cast_tilt_exact(const Camera& camera, const RaycastOptions& options, ColorImage& color, DepthImage& depth,
                         RaycastStats& stats);
    void cast_tilt_guedes(const Camera& camera, const RaycastOptions& options, ColorImage& color, DepthImage& depth,
                          RaycastStats& stats);
    // Casts columns [c0, c1), at most kShearBlock of them (one block; throws
    // std::logic_error otherwise): pixel (row j, column c) of the unfogged sample
    // color and of the slice index go to color/slice[(c - c0) * col_stride +
    // j * row_stride]; jend[c - c0] receives the painted count. Returns the
    // samples visited.
    long long cast_columns(const RaycastOptions& options, int c0, int c1, std::uint32_t* color, std::uint32_t* slice,
                           int* jend, std::ptrdiff_t col_stride, std::ptrdiff_t row_stride) const;
    // cast_columns for one CastKernel: the body, compiled for x86-64-v3 in _v3.
    long long cast_columns_body(const RaycastOptions& options, int c0, int c1, std::uint32_t* color,
                                std::uint32_t* slice, int* jend, std::ptrdiff_t col_stride,
                                std::ptrdiff_t row_stride) const;
    long long cast_columns_v3(const RaycastOptions& options, int c0, int c1, std::uint32_t* color, std::uint32_t* slice,
                              int* jend, std::ptrdiff_t col_stride, std::ptrdiff_t row_stride) const;
    // cast_columns for one-cell slices and the `blocks` surface, at most
    // kShearBlock columns. kStride: row stride of the output; kEvenRows: the
    // rows are evenly spaced in slope (shear) and the output has kPaintRows
    // rows of padding.
    template <std::ptrdiff_t kStride, bool kEvenRows>
    long long cast_blocks(int c0, int c1, std::uint32_t* color, std::uint32_t* slice, int* jend,
                          std::ptrdiff_t col_stride) const;
    template <bool kBilinear, bool kVarying>
    int cast_column(int c, std::uint32_t* color, std::uint32_t* slice, std::ptrdiff_t stride, long long& visited) const;

    const Terrain& terrain_;
    const Environment& env_;
    std::vector<std::uint32_t> colors_;      // packed sample colors, row-major
    std::unique_ptr<HeightPyramid> pyramid_; // --lod
    HeightPyramid max_pyramid_;              // heights only: run skipping
    RayMarcher marcher_;                     // tilt pixels past the vertical

    // Per-frame tables (reused).
    double eye_gx_ = 0, eye_gz_ = 0, eye_y_ = 0;
    double fx_ = 0, fz_ = 0, rx_ = 0, rz_ = 0;   // F and R, XZ
    std::vector<double> slice_d_;      // view depth along F of slice k
    std::vector<float> slice_df_;      // the same in float (fog distance)
    std::vector<float> slice_a_;       // v_scale / d_k
    std::vector<float> slice_b_;       // (y0 - eye_y) / d_k
    std::vector<float> slice_smax_;    // max over k' >= k of (max height - eye_y) / d_k'
    // Shear: what cast_blocks_column reads per slice, in one record.
    struct SliceGuess {
        std::int64_t ga, gb; // (raw ga + gb) >> kGuessBits: RowSearch's guess of the row a sample reaches
        float a, b;          // slice_a_, slice_b_: sigma = raw a + b
    };
    std::vector<SliceGuess> slice_guess_;
    std::vector<float> slice_depth_;   // window depth of slice k (shear)
    std::vector<std::uint8_t> slice_level_; // LOD level of slice k
    float max_height_ = 0;             // world, over all samples
    const std::uint16_t* level_heights_[32] = {};
    const std::uint32_t* level_colors_[32] = {};
    int level_cols_[32] = {};
    std::vector<float> row_m_;         // ray slope of row j (bottom-up), +inf sentinel at the end
    std::vector<double> col_a_;        // column plane: horizontal direction F + a R
    std::vector<double> col_ux_, col_uz_; // grid units per unit of d along the column
    std::vector<int> col_k0_, col_k1_; // slices inside the terrain
    int rows_cast_ = 0;
    bool rows_even_ = false;           // row_m_ evenly spaced (shear): cast_blocks_column searches rows
    bool uniform_slices_ = true;       // one cell apart: incremental stepping
    bool skip_runs_ = true;            // RaycastOptions::skip_runs
    SkyTable sky_;
    FogTable fog_;
    std::uint32_t fog_color_ = 0;
    struct BlockScratch {
        std::vector<std::uint32_t> color, slice;
        std::vector<int> jend;
    };
    tbb::enumerable_thread_specific<BlockScratch> block_scratch_;
    // Whole-image scratch for tilt (shear uses per-thread block scratch).
    std::vector<std::uint32_t> tilt_color_, tilt_slice_;
    std::vector<int> tilt_jend_;
    TiltRows tilt_rows_;
};

} // namespace overflight
