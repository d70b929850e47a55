// The Floating Horizon for the shear camera, the papers' case: vertical view
// plane, horizon shifted by fp tan(pitch). Column c is the plane
// F + (u_c/fp) R; row j (bottom-up) has slope (v_j + fp tan p)/fp; slices run
// from near to far along F, which is the view axis, so slice k's window depth
// is the depth vector entry (eq. 7).
//
// Based on: Szenberg, Gattass, Carvalho, "An Algorithm for the Visualization
// of a Terrain with Objects", SIBGRAPI 1997, Algorithm 1, sec. 5.1-5.2,
// eq. 7 and Algorithm 2, sec. 6.
#include "core/Parallel.h"
#include "raycast/FloatingHorizonState.h"
#include "raycast/ShearDrape.h"
#include "raycast/ShearResolve.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <atomic>

namespace overflight {

namespace {

// Multiplies the light painted into a block by the imagery under each
// painted pixel (ImageryTexels.h: drape_column, row by row: ShearDrape.h);
// column i's plane runs along F + a_i R, F and R horizontal for the shear camera.
void apply_imagery(const FloatingHorizonState& s, const Camera& camera, const RaycastOptions& options, int c0,
                   const ShearBlock& blk, std::uint32_t* color, const std::uint32_t* slice) {
    const glm::dvec3 F = camera.forward(), R = camera.right();
    DrapeFrame frame{&s.imagery, s.frame.slices.df.data(), s.frame.slices.df[0], s.frame.rows.m.data(),
                     float(camera.eye.x), float(camera.eye.z)};
    if (s.frame.slices.uniform) {
        frame.d_first = s.frame.slices.df[0];
        frame.d_step = float(s.frame.slices.step);
    }
    float dir_x[kShearBlock], dir_z[kShearBlock];
    for (int i = 0; i < blk.n; ++i) {
        const double a = s.frame.columns.a[std::size_t(c0 + i)];
        dir_x[i] = float(F.x + a * R.x);
        dir_z[i] = float(F.z + a * R.z);
    }
    drape_shear_block(frame, dir_x, dir_z, blk.n, blk.jend, color, slice, options.resolve);
}

// Casts and resolves the blocks of kShearBlock columns in parallel: a block
// is cast into a per-thread scratch that stays in L2 and resolved from there
// into runs of kShearBlock pixels of image rows (ShearResolve). Images start
// a cache line (ImageAllocator), so at widths that are multiples of 16 every
// full block writes each depth row as whole lines that no other block writes.
void cast_and_resolve_blocks(FloatingHorizonState& s, const Camera& camera, const RaycastOptions& options,
                             ColorImage& color, DepthImage& depth, RaycastStats& stats) {
    const auto t0 = Clock::now();
    const int W = camera.width, H = camera.height;
    const CastFrame& f = s.frame;
    ShearResolveTables tables{f.rows.m.data(), s.slice_depth.data(), f.slices.df.data(), &s.fog, s.fog_color,
                              s.sky.entries()};
    tables.slices = int(f.slices.df.size());
    if (f.slices.even > 0) {
        tables.d_first = f.slices.df[0];
        tables.d_step = float(f.slices.step);
        tables.even = f.slices.even;
    }
    if (s.air_on) {
        tables.air = &s.air;
        tables.sun_y = float(s.sun.y);
    }
    // The sun along each column's plane direction F + a R, per unit of view depth.
    const glm::dvec3 F = camera.forward(), R = camera.right();
    const double f_sun = glm::dot(F, s.sun), r_sun = glm::dot(R, s.sun);
    const int blocks = (W + kShearBlock - 1) / kShearBlock;
    std::atomic<long long> visited{0}, painted{0};
    // Thread time of each step, summed over the blocks (nanoseconds).
    std::atomic<long long> cast_ns{0}, resolve_ns{0};
    const bool backwards = s.blocks_backwards;
    s.blocks_backwards = !backwards;
    parallel::for_each_index(0, blocks, [&](int nth) {
        const int b = backwards ? blocks - 1 - nth : nth;
        const auto tc = Clock::now();
        FloatingHorizonState::BlockScratch& sc = s.block_scratch.local();
        const std::size_t need = std::size_t(kShearBlock) * std::size_t(H + kPaintRows);
        if (sc.pixels.size() < 2 * need) sc.pixels.resize(2 * need);
        std::uint32_t* const block_color = sc.pixels.data();
        std::uint32_t* const block_slice = block_color + need;
        if (sc.jend.size() < std::size_t(kShearBlock)) sc.jend.resize(kShearBlock);
        const int c0 = b * kShearBlock, c1 = std::min(W, c0 + kShearBlock);
        visited += cast_columns(s.terrain, f, options, c0, c1, block_color, block_slice, sc.jend.data(), 1,
                                kShearBlock);
        long long px = 0;
        for (int c = c0; c < c1; ++c) px += sc.jend[std::size_t(c - c0)];
        painted += px;
        ShearBlock blk;
        blk.n = c1 - c0;
        for (int i = 0; i < kShearBlock; ++i) {
            const double a = i < blk.n ? f.columns.a[std::size_t(c0 + i)] : 0.0;
            blk.len2[i] = float(1.0 + a * a);
            blk.jend[i] = i < blk.n ? sc.jend[std::size_t(i)] : 0;
            blk.sun_dot[i] = float(f_sun + a * r_sun);
        }
        if (s.imagery.bound()) apply_imagery(s, camera, options, c0, blk, block_color, block_slice);
        const auto tr = Clock::now();
        resolve_shear_block(tables, blk, H, block_color, block_slice, color.pixels.data() + c0,
                            depth.pixels.data() + c0, std::size_t(W), options.resolve);
        const auto te = Clock::now();
        cast_ns += std::chrono::duration_cast<std::chrono::nanoseconds>(tr - tc).count();
        resolve_ns += std::chrono::duration_cast<std::chrono::nanoseconds>(te - tr).count();
    });
    // Cast and resolve are fused per block (the block's scratch stays in L2),
    // so the step's wall time is split between them in proportion to the
    // thread time each took.
    const double ms_fused = ms_since(t0);
    const double thread_ns = double(cast_ns + resolve_ns);
    const double resolve_share = thread_ns > 0 ? double(resolve_ns) / thread_ns : 0.0;
    stats.ms_resolve = ms_fused * resolve_share;
    stats.ms_cast = ms_fused - stats.ms_resolve;
    stats.samples_visited = visited;
    stats.pixels_painted = painted;
}

} // namespace

void cast_shear(FloatingHorizonState& s, const Camera& camera, const Environment& env, const RaycastOptions& options,
                ColorImage& color, DepthImage& depth, RaycastStats& stats) {
    const auto t0 = Clock::now();
    CastFrame& f = s.frame;
    s.prepare_slices(camera, options, camera.near, camera.far, camera.focal_px());
    if (cast_reads_records(options)) s.terrain.prepare_records();
    shear_column_planes(camera, f.columns.a);
    // The columns' clipping (in parallel itself) beside the rows' tables:
    // the serial setup is a few per cent of a 4K frame.
    parallel::invoke([&] { clip_columns(f.view, s.terrain.terrain, f.slices, f.columns); },
                     [&] {
                         shear_rows(camera, f.rows);
                         slice_guesses(f.slopes, f.rows, f.guesses);
                         s.fog.build(env.fog_density, shear_fog_reach(camera, f.rows));
                     });
    if (s.imagery.bound()) {
        s.imagery.prepare_slices(f.slices.df.data(), int(f.slices.df.size()), camera.focal_px());
        s.imagery.prepare_rows(f.rows.m.data(), f.rows.count);
    }
    stats.ms_setup = ms_since(t0);
    stats.columns = camera.width;
    cast_and_resolve_blocks(s, camera, options, color, depth, stats);
}

} // namespace overflight
