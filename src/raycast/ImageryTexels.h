#pragma once
// The imagery (core/ImageryPyramid.h) as the ray casters read it: the albedo
// of a painted sample is the texel under the sample's exact ground position
// (x, z of the ray at its slice, not the cell's corner) on the mip level of
// the pixel's footprint there (Williams, "Pyramidal Parametrics", SIGGRAPH
// 1983, sec. 3: level = log2(footprint / texel)), nearest texel at that level.
// The footprint is the longer side of the pixel's trace on level ground, as
// GL's isotropic level takes the longer of the texture derivatives: across
// the ray d / fp at view depth d (fp the focal length in pixels), along it
// d / (fp |m|) for a ray of slope m (rise per unit view depth, m < 0 looking
// down); for rays level or rising, d / fp. So log2(footprint / texel) is a
// term per slice plus a term per row, both tabulated per frame.
//
// With imagery, the casts paint the light of each sample instead of its
// color (core/SunLight.h, LightOutput::Light: 128 is a light of 1), and the
// albedo multiplies it here, before fog or aerial perspective: the sun, the
// shadows and the atmosphere stay as they are without imagery.
#include "core/ImageryPyramid.h"

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace overflight {

class ImageryTexels {
public:
    // The pyramid to read (it must outlive its use); null: none.
    void bind(const ImageryPyramid* pyramid);
    bool bound() const { return pyramid_ != nullptr; }

    // log2(d_k / (fp texel)) of every slice from its view depth slice_d[k],
    // for a camera of focal length focal_px (pixels).
    void prepare_slices(const float* slice_d, int slices, double focal_px);
    // log2(1 / |m_j|) of every row from its slope row_m[j] (0 for m_j >= 0);
    // after prepare_slices, whose slices level_starts() searches.
    void prepare_rows(const float* row_m, int rows);
    // The mip level of a pixel of row j painted from slice k.
    int level(int k, int j) const {
        const float l = slice_log2_[std::size_t(k)] + row_log2_[std::size_t(j)] + 0.5f;
        return l < 1.0f ? 0 : std::min(int(l), last_level_);
    }

    // The texel of `level` under world (x, z), clamped to the imagery's edge.
    Rgba8 at(float x, float z, int level) const {
        const Level& l = levels_[std::size_t(level)];
        const int col = std::clamp(int((x - x0_) * l.inv_x), 0, l.w - 1);
        const int row = std::clamp(int((z - z0_) * l.inv_z), 0, l.h - 1);
        return texels_.data()[std::size_t(l.first) + tiled_index(col, row, l.tiles_x)];
    }

    // The texels are a tiled copy of the pyramid's row-major levels, so that
    // the rays of neighbouring pixels, which meet the ground at neighbouring
    // texels in whatever direction the view runs over the imagery, read the
    // same cache lines and pages: a level is cut into pages of 32 x 32 texels
    // (4 KiB, row-major over the level), a page into 8 x 8 lines of 4 x 4
    // texels (64 bytes, row-major within the page), a line row-major. (Two
    // levels of the blocking of Hakura and Gupta, "The Design and Analysis of
    // a Cache Architecture for Texture Mapping", ISCA 1997, sec. 4.) A level
    // of w x h texels takes tiles_x = ceil(w / 32) pages per page row. The
    // copy is made once by bind(): the caster holds the imagery twice (the
    // pyramid stays row-major for the GL methods).
    static constexpr int kPageSide = 32;
    static std::size_t tiled_index(int col, int row, int tiles_x) {
        const unsigned c = unsigned(col), r = unsigned(row);
        const std::size_t page = std::size_t(r >> 5) * std::size_t(tiles_x) + (c >> 5);
        return (page << 10) | ((r & 28u) << 5) | ((c & 28u) << 2) | ((r & 3u) << 2) | (c & 3u);
    }

    // What level() and at() read, for kernels that compute them lane by lane
    // (ShearDrape.h): the tables per slice and per row, the pyramid's origin
    // and last level, and each level's size, scale and place in texels().
    struct Level {
        int w = 1, h = 1;
        float inv_x = 1, inv_z = 1; // texels per world unit
        int tiles_x = 1;            // pages per page row
        std::int64_t first = 0;     // index in texels() of the level's first texel
    };
    const float* slice_log2() const { return slice_log2_.data(); }
    const float* row_log2() const { return row_log2_.data(); }
    float x0() const { return x0_; }
    float z0() const { return z0_; }
    int last_level() const { return last_level_; }
    const Level& level_at(int level) const { return levels_[std::size_t(level)]; }
    // Every level's tiled texels, one after the other.
    const Rgba8* texels() const { return texels_.data(); }
    // The same per level as tables of 16 entries, which a kernel picks from
    // with two permutes rather than gathers; present (lane_tables()) while
    // the pyramid has at most 16 levels and every texel's index fits in 32 bits.
    struct LevelLanes {
        static constexpr int kLevels = 16;
        alignas(32) float inv_x[kLevels] = {}, inv_z[kLevels] = {};
        alignas(32) int w[kLevels] = {}, h[kLevels] = {}, tiles_x[kLevels] = {}, first[kLevels] = {};
    };
    const LevelLanes& level_lanes() const { return lanes_; }
    bool lane_tables() const { return lane_tables_; }
    // With lane tables, the first slice of every level along row j: entry L
    // is the smallest k with level(k, j) >= L (0 for L = 0; INT32_MAX where
    // no slice reaches L, and past the last level). level(k, j) only grows
    // with k (view depths grow along the slices), so it is the number of
    // entries L >= 1 at or below k: a kernel finds it by a binary search in
    // 16 entries (four permutes) instead of gathering the slice's term, and
    // gets the same level.
    struct LevelStarts {
        alignas(64) std::int32_t k[LevelLanes::kLevels];
    };
    const LevelStarts& level_starts(int j) const { return level_starts_[std::size_t(j)]; }

private:
    const ImageryPyramid* pyramid_ = nullptr;
    std::vector<Level> levels_;
    std::vector<Rgba8> texels_;
    LevelLanes lanes_;
    bool lane_tables_ = false;
    float x0_ = 0, z0_ = 0;
    int last_level_ = 0;
    std::vector<float> slice_log2_, row_log2_;
    std::vector<LevelStarts> level_starts_;
    std::vector<float> starts_of_slices_, starts_of_rows_; // the terms level_starts_ were found for
};

// One cast column of a floating horizon over vertical planes, as the cast
// left it: pixel j (bottom-up) at color[j * row_stride], painted from slice
// slice[j * row_stride] while j < jend. Each painted pixel's light becomes
// light x the texel under the point where its ray meets the surface: a run
// of rows painted by the sample of slice k, whose top row's ray passes
// (within a pixel) over the sample's height, sees that height at view depth
// d_k m_top / m_j along row j's ray (slope m_j per unit view depth, negative
// downwards), clamped to [d_{k-1}, d_k], the cell the sample stands for;
// the point is eye + d (dir_x, dir_z), dir the plane's horizontal direction
// per unit view depth. Without that clamp every row of the run would show
// the texel at slice k, stretching one texel over a cell's depth.
struct DrapeFrame {
    const ImageryTexels* imagery = nullptr;
    const float* slice_d = nullptr; // view depth of slice k
    float d_before_first = 0;       // the view depth before slice 0 (the near plane)
    const float* row_m = nullptr;   // slope of row j, bottom-up
    float eye_x = 0, eye_z = 0;
    // Evenly spaced slices (d_step > 0): slice_d[k] is d_first + d_step * k,
    // computed in float in that order, so a kernel may compute it rather than
    // read it (ShearResolveTables' convention). 0: read slice_d.
    float d_first = 0, d_step = 0;
};
void drape_column(const DrapeFrame& f, float dir_x, float dir_z, std::uint32_t* color, const std::uint32_t* slice,
                  int jend, std::ptrdiff_t row_stride);

// A run of rows painted from one slice, as drape_column finds it.
struct DrapeRun {
    std::uint32_t k = ~0u; // the slice (~0: none yet)
    float dk = 0, d_prev = 0, m_top = 0;
};
// The run of slice k starting at row j of a column of `jend` painted rows
// whose slice indices are slice[j * row_stride].
DrapeRun drape_run(const DrapeFrame& f, const std::uint32_t* slice, int j, int jend, std::ptrdiff_t row_stride);
// Pixel j of `run`: its light times the texel under its ground point.
inline std::uint32_t drape_pixel(const DrapeFrame& f, const DrapeRun& run, float dir_x, float dir_z, int j,
                                 std::uint32_t light);

// light (128 = 1) x albedo per channel, rounded, clamped to 255.
inline Rgb8 modulate_light(Rgb8 light, Rgba8 albedo) {
    auto m = [](unsigned l, unsigned a) { return std::uint8_t(std::min<unsigned>((l * a + 64) >> 7, 255)); };
    return Rgb8{m(light.r, albedo.r), m(light.g, albedo.g), m(light.b, albedo.b)};
}

// light (packed 0x00BBGGRR, 128 = 1, up to 255) x albedo, rounded, clamped to 255.
inline std::uint32_t modulate_light(std::uint32_t light, Rgba8 albedo) {
    const std::uint32_t r = std::min<std::uint32_t>(((light & 0xFFu) * albedo.r + 64) >> 7, 255);
    const std::uint32_t g = std::min<std::uint32_t>((((light >> 8) & 0xFFu) * albedo.g + 64) >> 7, 255);
    const std::uint32_t b = std::min<std::uint32_t>((((light >> 16) & 0xFFu) * albedo.b + 64) >> 7, 255);
    return r | (g << 8) | (b << 16);
}

inline std::uint32_t drape_pixel(const DrapeFrame& f, const DrapeRun& run, float dir_x, float dir_z, int j,
                                 std::uint32_t light) {
    const float m = f.row_m[j];
    // Rays looking down meet the sample's height in front of slice k; others hit its face at d_k.
    const float d = run.m_top < 0.0f && m < 0.0f ? std::clamp(run.dk * (run.m_top / m), run.d_prev, run.dk) : run.dk;
    return modulate_light(light, f.imagery->at(f.eye_x + d * dir_x, f.eye_z + d * dir_z, f.imagery->level(int(run.k), j)));
}

} // namespace overflight
