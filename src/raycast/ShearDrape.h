#pragma once
// The imagery draped over a shear block (ImageryTexels.h, drape_column) row
// by row rather than column by column, so that the lanes of a row are
// computed together: each lane keeps the slope of its current run's top row
// while the rows are walked top-down (a run's top is the first row met), and
// the texel fetches of a row's lanes are independent loads in flight
// together. Same bits as drape_column on every column: the same float
// operations in the same order, lane by lane.
#include "raycast/ImageryTexels.h"
#include "raycast/ShearResolve.h" // kShearBlock, ResolveKernel

#include <cstdint>

namespace overflight {

// Drapes the block's columns i < n: column i's plane runs along (dir_x[i],
// dir_z[i]) per unit of view depth, its painted rows are j < jend[i], its
// pixel j at color/slice[j * kShearBlock + i] (ShearResolve.h's scratch).
// Evenly spaced slices (f.d_step > 0) let the Avx512 kernel compute view
// depths rather than read them. ResolveKernel::Avx2, Avx2Loads (its tables
// read with scalar loads rather than gathers, LaneLookup.h; Avx2Window drapes
// as Avx2Loads: the texels of neighbouring lanes are not neighbours) and
// Avx512 (8, 8 and 16 lanes, the same bits) must be resolve_kernel_available(); Auto picks
// the wider one the CPU has (Avx2Loads where gathers are slow,
// cpu_gathers_slow: on a Zen 1 EPYC it drapes in 12 % less time than Avx2,
// measured), else runs drape_column per column
// (ResolveKernel::Portable), as all do for imagery without lane tables
// (ImageryTexels::lane_tables).
void drape_shear_block(const DrapeFrame& f, const float* dir_x, const float* dir_z, int n, const int* jend,
                       std::uint32_t* color, const std::uint32_t* slice, ResolveKernel kernel = ResolveKernel::Auto);

} // namespace overflight
