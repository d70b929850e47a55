#pragma once
// The block cast of the Floating Horizon (private to src/raycast): Algorithm 1
// of Szenberg, Gattass, Carvalho, "An Algorithm for the Visualization of a
// Terrain with Objects", SIBGRAPI 1997, over a block of at most kShearBlock
// columns, given the frame's tables (FloatingHorizonTables.h). Each pixel
// painted gets the unfogged sample color and the index of its slice; fog,
// sky and depth are the resolve's business.
//
// One body (FloatingHorizonCast.inl) compiled once per instruction set
// (CastKernel): FloatingHorizonCast.cpp for the baseline, which also picks
// the kernel at run time, FloatingHorizonCastX86_64_v3.cpp for x86-64-v3,
// FloatingHorizonCastX86_64_v4.cpp for x86-64-v4 (its own kernel for the
// shear camera's evenly spaced slices: 16 columns in lockstep).
#include "core/SunLight.h"
#include "core/Terrain.h"
#include "raycast/FloatingHorizonTables.h"
#include "raycast/HeightPyramid.h"
#include "raycast/RaycastOptions.h"
#include "raycast/ShearResolve.h" // kShearBlock: the cast's block is the resolve's

#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

namespace overflight {

// Rows that every sample of the shear cast (evenly spaced rows) writes from
// the horizon up, painted or not: a block's scratch has that many rows of
// padding. A visited sample paints 1.3 rows on average on the bench view;
// measured there: 2 and 8 are 5-10 % slower than 4.
constexpr int kPaintRows = 4;

// The terrain as the cast samples it: level 0 is the terrain (colors packed
// 0x00BBGGRR), levels 1.. the distance LOD's max-height / mean-color pyramid
// (built on first use); the max-height pyramid bounds runs of slices.
struct CastTerrain {
    static constexpr int kMaxLevels = 32;
    // Levels of the max-height pyramid (level L: 2^L samples square): a
    // coarse run of 32 slices spans 32 / cos(theta) samples, so 12 levels
    // serve columns up to 89 degrees off the view axis.
    static constexpr int kRunLevels = 12;

    explicit CastTerrain(const Terrain& terrain);
    // Builds the LOD pyramid if needed; returns its deepest level (<= 31).
    int lod_levels();
    // Paints `sample_colors` (one per sample, e.g. sun-lit; null: the
    // terrain's own) from now on: repacks level 0, drops the LOD pyramid.
    // With `mask` (the light mask the colors were lit with), a front face's
    // light changes halfway between a shadowed and a lit sample
    // (FrontFace.h): the mask goes into the packed colors' top byte and
    // mask.other_colors is read where it does (it must outlive its use).
    void set_colors(const std::vector<Rgb8>* sample_colors, const LightMask& mask = {});
    // Builds `records` if they are not built (kept up to date by set_colors
    // from then on). Not thread-safe: call before casting.
    void prepare_records();

    const Terrain& terrain;
    float max_height = 0; // world, over all samples
    float min_height = 0; // world, over all samples (the aerial perspective's height range)
    const std::vector<Rgb8>* source_colors = nullptr; // what `colors` packs; null: terrain.colors()
    std::vector<std::uint32_t> colors; // 0x00BBGGRR, kShadowedBit (FrontFace.h) where the mask shadows
    const Rgb8* other_colors = nullptr; // LightMask::other_colors; null: no mask
    // Level 0's packed color and raw height side by side, colors[i] |
    // heights[i] << 32, for the kernel that gathers the samples of 16 columns
    // at once (x86-64-v4): there two gathers of 8 records cost about half of
    // one gather of 16 heights and one of 16 colors, and a sample's prefetch
    // touches one cache line instead of two. Empty until prepare_records():
    // 8 bytes per sample on top of `colors`.
    std::vector<std::uint64_t> records;
    HeightPyramid max_pyramid; // heights only: run skipping
    std::unique_ptr<HeightPyramid> lod_pyramid;
    const std::uint16_t* level_heights[kMaxLevels] = {};
    const std::uint32_t* level_colors[kMaxLevels] = {};
    int level_cols[kMaxLevels] = {};
};

// One frame's tables, as the cast reads them.
struct CastFrame {
    ViewAxes view;
    Slices slices;
    SliceSlopes slopes;
    std::vector<SliceGuess> guesses; // rows.even only
    Columns columns;
    Rows rows;
    bool skip_runs = true; // RaycastOptions::skip_runs, where the bound holds (v_scale > 0)
};

// Casts columns [c0, c1), at most kShearBlock of them (one block; throws
// std::logic_error otherwise): pixel (row j, column c) of the unfogged sample
// color and of the slice index go to color/slice[(c - c0) * col_stride +
// j * row_stride]; jend[c - c0] receives the painted count. The row stride
// is kShearBlock (a block's scratch) or 1 (a whole-image scratch, column-major).
// Returns the samples visited. Runs the kernel options.kernel asks for, or
// with CastKernel::Auto the fastest this CPU runs.
long long cast_columns(const CastTerrain& terrain, const CastFrame& frame, const RaycastOptions& options, int c0,
                       int c1, std::uint32_t* color, std::uint32_t* slice, int* jend, std::ptrdiff_t col_stride,
                       std::ptrdiff_t row_stride);

// Whether cast_columns runs, for these options on this CPU, the kernel that
// reads CastTerrain::records (call prepare_records() before it casts).
bool cast_reads_records(const RaycastOptions& options);

// The same compiled for one instruction set each (cast_columns picks).
long long cast_columns_portable(const CastTerrain& terrain, const CastFrame& frame, SurfaceModel surface, int c0,
                                int c1, std::uint32_t* color, std::uint32_t* slice, int* jend,
                                std::ptrdiff_t col_stride, std::ptrdiff_t row_stride);
long long cast_columns_x86_64_v3(const CastTerrain& terrain, const CastFrame& frame, SurfaceModel surface, int c0,
                                 int c1, std::uint32_t* color, std::uint32_t* slice, int* jend,
                                 std::ptrdiff_t col_stride, std::ptrdiff_t row_stride);
long long cast_columns_x86_64_v4(const CastTerrain& terrain, const CastFrame& frame, SurfaceModel surface, int c0,
                                 int c1, std::uint32_t* color, std::uint32_t* slice, int* jend,
                                 std::ptrdiff_t col_stride, std::ptrdiff_t row_stride);

} // namespace overflight
