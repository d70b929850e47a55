#pragma once
// The resolve step of the Floating Horizon for the `shear` camera: turns what
// Algorithm 1 painted into a block of columns (per pixel: the sample color and
// the slice index) into image pixels with OpenGL window depth, fog and sky.
//
// Based on: Szenberg, Gattass, Carvalho 1997, sec. 5.2 (slices parallel to the
// screen: every pixel painted from slice k has the window depth of the depth
// vector entry k, eq. 7, Algorithm 2) and sec. 6 (the depth is stored with
// every painted pixel so that Z-buffered objects composite on it); fog and sky
// follow the conventions of Atmosphere.h that the GL renderers share.
//
// Layout: a block is kShearBlock adjacent image columns. Its scratch is
// row-major, kShearBlock entries per row, rows counted bottom-up (the order in
// which Algorithm 1 paints); the images are row-major, top-down.
#include "core/Image.h"
#include "raycast/Atmosphere.h"
#include "raycast/RaycastOptions.h" // ResolveKernel

#include <cstddef>
#include <cstdint>

namespace overflight {

constexpr int kShearBlock = 32; // image columns per block

// Per-frame tables, shared by all blocks.
struct ShearResolveTables {
    const float* row_m = nullptr;       // ray slope of row j (bottom-up), per unit of view depth
    const float* slice_depth = nullptr; // window depth of slice k (eq. 7)
    const float* slice_d = nullptr;     // view depth of slice k
    const FogTable* fog = nullptr;
    std::uint32_t fog_color = 0;        // 0x00BBGGRR
    const std::uint32_t* sky = nullptr; // SkyTable::entries()
    // Environment::atmosphere: the aerial perspective and its sky instead of
    // fog and sky gradient; sun_y is the sun direction's Y.
    const AerialTables* air = nullptr;
    float sun_y = 0.0f;
    // The first `even` slices evenly spaced (d_step > 0): slice_d[k] is
    // d_first + d_step * k for k < even, computed in float in that order, so
    // a kernel may compute it rather than read it. 0: read slice_d.
    float d_first = 0.0f, d_step = 0.0f;
    int even = 0;
    // The entries of slice_depth and slice_d (0: unknown, so that a kernel
    // reads them one lane at a time).
    int slices = 0;
};

// One block as the cast left it.
struct ShearBlock {
    int n = 0;                 // image columns in the block (<= kShearBlock; the rest is padding)
    float len2[kShearBlock];   // |F + a R|^2 of each column's plane (1 for padding)
    int jend[kShearBlock];     // pixels painted, bottom-up (0 for padding)
    float sun_dot[kShearBlock]; // with air: (F + a R) . sun of each column's plane (0 for padding)
};

// The kernel that computes the pixels (RaycastOptions.h: all give the same
// bits). Avx2 reads its tables with gathers, Avx2Loads with scalar loads,
// Avx2Window through 8-entry windows permuted in registers, with scalar loads
// where a lane falls outside (LaneLookup.h); where gathers are slow
// (cpu_gathers_slow) Auto picks Avx2Window for the resolve and Avx2Loads for
// the imagery's drape. Avx512 (AVX-512 F, BW, DQ and VL) has kernels of its
// own for the aerial perspective and for GL_EXP fog with the sky gradient
// (16 lanes, the tables read from windows permuted in registers) and in the
// imagery's drape (ShearDrape.h). Simd128 is WebAssembly's (a
// build with -msimd128): the GL_EXP fog and sky gradient in 4 lanes; the
// aerial perspective runs the portable kernel there.
bool resolve_kernel_available(ResolveKernel kernel);

// Resolves rows [0, H) of a block. color/slice hold, at j * kShearBlock + i,
// the unfogged sample color (0x00BBGGRR) and the slice index of pixel j
// (bottom-up) of column i wherever j < jend[i]; other entries may hold
// anything. Pixel j < jend[i] gets the color fogged at the eye distance
// d_k |ray_j| (with air: seen through the air at that distance and the height
// d_k m_j above the eye) and depth slice_depth[k]; the others get the sky
// color of their ray's elevation (with air: and angle to the sun) and depth 1. The results are written to out_c/out_d (the
// images at the block's first column, W pixels per row), blk.n pixels per
// row and no more; the depth may be written with streaming stores, which a
// fence orders before the call returns.
void resolve_shear_block(const ShearResolveTables& t, const ShearBlock& blk, int H, const std::uint32_t* color,
                         const std::uint32_t* slice, Rgb8* out_c, float* out_d, std::size_t W,
                         ResolveKernel kernel = ResolveKernel::Auto);

} // namespace overflight
