// The block cast compiled for the baseline instruction set, the terrain it
// samples, and the run-time pick of the kernel (CastKernel). See
// FloatingHorizonCast.h.
#include "raycast/FloatingHorizonCast.inl"

#include "core/HugePages.h"
#include "core/Parallel.h"
#include "raycast/FloatingHorizon.h"

namespace overflight {

CastTerrain::CastTerrain(const Terrain& t)
    : terrain(t), max_height(t.max_height()), min_height(t.min_height()), max_pyramid(t, kRunLevels) {
    set_colors(nullptr);
    level_heights[0] = t.heights().data();
    level_cols[0] = t.cols();
}

void CastTerrain::set_colors(const std::vector<Rgb8>* sample_colors, const LightMask& mask) {
    source_colors = sample_colors;
    const std::vector<Rgb8>& from = sample_colors ? *sample_colors : terrain.colors();
    if (colors.size() != from.size()) assign_on_huge_pages(colors, from.size());
    const std::uint8_t* shadowed = mask.shadowed ? mask.shadowed->data() : nullptr;
    other_colors = shadowed ? mask.other_colors->data() : nullptr;
    const std::size_t grain = std::size_t(1) << 16;
    parallel::for_each_range(std::size_t(0), from.size(), grain, [&](std::size_t begin, std::size_t end) {
        if (shadowed)
            for (std::size_t i = begin; i < end; ++i)
                colors[i] = pack_rgb(from[i]) | (shadowed[i] ? kShadowedBit : 0u);
        else
            for (std::size_t i = begin; i < end; ++i) colors[i] = pack_rgb(from[i]);
    });
    level_colors[0] = colors.data();
    lod_pyramid.reset();
    if (!records.empty()) {
        records.clear();
        prepare_records();
    }
}

void CastTerrain::prepare_records() {
    if (!records.empty()) return;
    assign_on_huge_pages(records, colors.size());
    const std::uint16_t* heights = terrain.heights().data();
    parallel::for_each_range(std::size_t(0), colors.size(), std::size_t(1) << 16,
                             [&](std::size_t begin, std::size_t end) {
                                 for (std::size_t i = begin; i < end; ++i)
                                     records[i] = colors[i] | (std::uint64_t(heights[i]) << 32);
                             });
}

int CastTerrain::lod_levels() {
    if (!lod_pyramid) {
        lod_pyramid = std::make_unique<HeightPyramid>(terrain, 12, colors.data());
        for (int L = 1; L <= std::min(lod_pyramid->levels(), kMaxLevels - 1); ++L) {
            level_heights[L] = lod_pyramid->level(L).heights.data();
            level_colors[L] = lod_pyramid->level(L).colors.data();
            level_cols[L] = lod_pyramid->level(L).cols;
        }
    }
    return std::min(lod_pyramid->levels(), kMaxLevels - 1);
}

long long cast_columns_portable(const CastTerrain& terrain, const CastFrame& frame, SurfaceModel surface, int c0,
                                int c1, std::uint32_t* color, std::uint32_t* slice, int* jend,
                                std::ptrdiff_t col_stride, std::ptrdiff_t row_stride) {
    return cast_columns_body(terrain, frame, surface, c0, c1, color, slice, jend, col_stride, row_stride);
}

// CastKernel::X86_64_v3 is built with GCC for x86-64 (src/CMakeLists.txt):
// GCC names the level in __builtin_cpu_supports.
bool cast_kernel_available(CastKernel kernel) {
    switch (kernel) {
    case CastKernel::Auto:
    case CastKernel::Portable: return true;
    case CastKernel::X86_64_v3:
#if OVERFLIGHT_CAST_X86_64_V3
        return __builtin_cpu_supports("x86-64-v3");
#else
        return false;
#endif
    case CastKernel::X86_64_v4:
#if OVERFLIGHT_CAST_X86_64_V4
        return __builtin_cpu_supports("x86-64-v4");
#else
        return false;
#endif
    }
    return false;
}

bool cast_reads_records(const RaycastOptions& options) {
#if OVERFLIGHT_CAST_X86_64_V4
    static const bool v4 = cast_kernel_available(CastKernel::X86_64_v4);
    return v4 && (options.kernel == CastKernel::Auto || options.kernel == CastKernel::X86_64_v4);
#else
    (void)options;
    return false;
#endif
}

long long cast_columns(const CastTerrain& terrain, const CastFrame& frame, const RaycastOptions& options, int c0,
                       int c1, std::uint32_t* color, std::uint32_t* slice, int* jend, std::ptrdiff_t col_stride,
                       std::ptrdiff_t row_stride) {
    if (c1 - c0 > kBlock) throw std::logic_error("FloatingHorizon: more columns than one block");
#if OVERFLIGHT_CAST_X86_64_V4
    if (cast_reads_records(options))
        return cast_columns_x86_64_v4(terrain, frame, options.surface, c0, c1, color, slice, jend, col_stride,
                                      row_stride);
#endif
#if OVERFLIGHT_CAST_X86_64_V3
    static const bool v3 = cast_kernel_available(CastKernel::X86_64_v3);
    if (v3 && options.kernel != CastKernel::Portable)
        return cast_columns_x86_64_v3(terrain, frame, options.surface, c0, c1, color, slice, jend, col_stride,
                                      row_stride);
#endif
    return cast_columns_portable(terrain, frame, options.surface, c0, c1, color, slice, jend, col_stride, row_stride);
}

} // namespace overflight
