// Based on: S. Macke, "Voxel Space"; A. LaMothe, "Tricks of the
// Game-Programming Gurus"; M. Freese's voxel landscape notes. See
// ClassicVoxelSpace.h.
#include "raycast/ClassicVoxelSpace.h"

#include "core/Error.h"
#include "core/Parallel.h"

#include <glm/trigonometric.hpp>

#include <algorithm>
#include <cmath>
#include <vector>

namespace overflight {

namespace {

// The lines' distances along the view axis, near to far inclusive (the
// Floating Horizon's slices d_k = near + k h_scale when the step is one sample).
std::vector<double> line_distances(const Camera& camera, double h_scale, const ClassicVoxelSpaceOptions& o) {
    std::vector<double> z;
    double step = o.first_step * h_scale;
    for (double d = camera.near; d <= camera.far; d += step, step *= o.step_growth) z.push_back(d);
    return z;
}

} // namespace

ClassicVoxelSpaceStats render_classic_voxel_space(const Terrain& terrain, const Camera& camera,
                                                  const ClassicVoxelSpaceOptions& options, ColorImage& color) {
    camera.validate();
    if (camera.projection != Projection::Shear)
        throw Error("camera", "the classic Voxel Space loop has vertical view planes only (shear projection)");
    if (!(options.first_step > 0.0) || !(options.step_growth >= 1.0) || !std::isfinite(options.step_growth))
        throw Error("camera", "the classic Voxel Space step must be positive and must not shrink");
    const int W = camera.width, H = camera.height;
    color.resize(W, H, options.sky);

    const std::vector<double> lines = line_distances(camera, terrain.h_scale(), options);
    const double fp = camera.focal_px();
    const double horizon = H * 0.5 + fp * std::tan(glm::radians(camera.pitch)); // row of the eye's height
    const glm::dvec3 F = camera.forward(), R = camera.right();
    const double inv_hs = 1.0 / terrain.h_scale();
    const double eye_y = camera.eye.y;
    const int rows = terrain.rows(), cols = terrain.cols();
    const std::uint16_t* heights = terrain.heights().data();
    const Rgb8* colors = terrain.colors().data();
    const float vs = terrain.v_scale(), y0 = terrain.y_offset();
    Rgb8* frame = color.pixels.data();

    parallel::for_each_range(0, W, 64, [&](int c0, int c_end) {
        const int n = c_end - c0;
        std::vector<int> ybuffer(std::size_t(n), H); // first row not yet painted below the horizon
        for (const double z : lines) {
            // The line at distance z across the view, in samples: column c's
            // point is eye + z F + z u_c / fp R.
            const double left_u = camera.u_of(c0) / fp;
            double x = (camera.eye.x + z * (F.x + left_u * R.x)) * inv_hs;
            double s = (camera.eye.z + z * (F.z + left_u * R.z)) * inv_hs;
            const double dx = z * R.x / fp * inv_hs, ds = z * R.z / fp * inv_hs;
            const double scale = fp / z;
            for (int i = 0; i < n; ++i, x += dx, s += ds) {
                const int col = int(x + 0.5), row = int(s + 0.5);
                if (x < -0.5 || s < -0.5 || col >= cols || row >= rows) continue;
                const std::size_t k = std::size_t(row) * std::size_t(cols) + std::size_t(col);
                const double top = horizon - (double(vs * float(heights[k]) + y0) - eye_y) * scale;
                const int first = std::max(0, int(std::ceil(top - 0.5)));
                int& y = ybuffer[std::size_t(i)];
                if (first >= y) continue;
                const Rgb8 paint = colors[k];
                for (int r = first; r < y; ++r) frame[std::size_t(r) * std::size_t(W) + std::size_t(c0 + i)] = paint;
                y = first;
            }
        }
    });
    ClassicVoxelSpaceStats stats;
    stats.lines = int(lines.size());
    stats.samples = std::uint64_t(lines.size()) * std::uint64_t(W);
    return stats;
}

} // namespace overflight
