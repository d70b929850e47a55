#include "core/Terrain.h"

#include "core/Error.h"
#include "core/HugePages.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <sstream>
#include <string>

namespace overflight {

Terrain::Terrain(int rows, int cols, float h_scale, float v_scale, float y_offset)
    : rows_(rows), cols_(cols), h_scale_(h_scale), v_scale_(v_scale), y_offset_(y_offset) {
    if (rows < 2 || cols < 2 || rows > 65537 || cols > 65537)
        throw Error("terrain", "size " + std::to_string(rows) + "x" + std::to_string(cols) +
                                   " is outside 2..65537 samples per side");
    if (const std::string problem = horizontal_scale_problem(rows, cols, h_scale); !problem.empty())
        throw Error("terrain", problem);
    if (!std::isfinite(v_scale) || !std::isfinite(y_offset))
        throw Error("terrain", "vertical scale and offset must be finite numbers");
    // The casts sample the grid in every frame (HugePages.h).
    assign_on_huge_pages(heights_, std::size_t(rows) * std::size_t(cols), std::uint16_t(0));
    assign_on_huge_pages(colors_, heights_.size(), Rgb8{128, 128, 128});
}

namespace {

std::string number(double v) {
    std::ostringstream s;
    s.precision(8); // 2^24 in full; a float read from a file without its noise digits
    s << v;
    return s.str();
}

} // namespace

std::string horizontal_scale_problem(int rows, int cols, double h_scale) {
    if (!(h_scale > 0) || !std::isfinite(h_scale)) return "horizontal scale " + number(h_scale) + " is not a positive number";
    const double extent = h_scale * double(std::max(rows, cols) - 1);
    if (extent > kWorldLimit)
        return "horizontal scale " + number(h_scale) + " makes the terrain " + number(extent) +
               " units across, beyond the " + number(kWorldLimit) + " (2^24) that float world coordinates hold";
    return {};
}

std::string elevation_problem(double elevation) {
    if (!std::isfinite(elevation)) return "elevation " + number(elevation) + " is not a finite number";
    if (std::abs(elevation) > kWorldLimit)
        return "elevation " + number(elevation) + " is beyond +-" + number(kWorldLimit) +
               " (2^24), where float world coordinates no longer hold whole units";
    return {};
}

float Terrain::height_nearest(float x, float z) const {
    const int col = std::clamp(int(std::lround(x / h_scale_)), 0, cols_ - 1);
    const int row = std::clamp(int(std::lround(z / h_scale_)), 0, rows_ - 1);
    return sample_height(row, col);
}

float Terrain::height_bilinear(float x, float z) const {
    const float gx = std::clamp(x / h_scale_, 0.0f, float(cols_ - 1));
    const float gz = std::clamp(z / h_scale_, 0.0f, float(rows_ - 1));
    const int c0 = std::min(int(gx), cols_ - 2);
    const int r0 = std::min(int(gz), rows_ - 2);
    const float fx = gx - float(c0);
    const float fz = gz - float(r0);
    const float h00 = float(raw(r0, c0)), h01 = float(raw(r0, c0 + 1));
    const float h10 = float(raw(r0 + 1, c0)), h11 = float(raw(r0 + 1, c0 + 1));
    const float top = h00 + (h01 - h00) * fx;
    const float bottom = h10 + (h11 - h10) * fx;
    return v_scale_ * (top + (bottom - top) * fz) + y_offset_;
}

glm::vec3 Terrain::normal(float x, float z) const {
    // Gradient of the bilinear surface by central differences one cell apart.
    const float d = h_scale_;
    const float dhdx = (height_bilinear(x + d, z) - height_bilinear(x - d, z)) /
                       (std::min(x + d, width()) - std::max(x - d, 0.0f));
    const float dhdz = (height_bilinear(x, z + d) - height_bilinear(x, z - d)) /
                       (std::min(z + d, depth()) - std::max(z - d, 0.0f));
    return glm::normalize(glm::vec3(-dhdx, 1.0f, -dhdz));
}

glm::vec3 Terrain::sample_normal(int row, int col) const {
    const int c0 = std::max(col - 1, 0), c1 = std::min(col + 1, cols_ - 1);
    const int r0 = std::max(row - 1, 0), r1 = std::min(row + 1, rows_ - 1);
    const float dhdx = (sample_height(row, c1) - sample_height(row, c0)) / (h_scale_ * float(c1 - c0));
    const float dhdz = (sample_height(r1, col) - sample_height(r0, col)) / (h_scale_ * float(r1 - r0));
    return glm::normalize(glm::vec3(-dhdx, 1.0f, -dhdz));
}

float Terrain::min_height() const {
    if (heights_.empty()) return 0;
    return v_scale_ * float(*std::min_element(heights_.begin(), heights_.end())) + y_offset_;
}

float Terrain::max_height() const {
    if (heights_.empty()) return 0;
    return v_scale_ * float(*std::max_element(heights_.begin(), heights_.end())) + y_offset_;
}

int next_pow2_plus1(int n) {
    int p = 1;
    while (p + 1 < n) p *= 2;
    return p + 1;
}

// A bit test rather than next_pow2_plus1(n) == n, which doubles past INT_MAX
// for n above 2^30 + 1 (a size read from a file may be anything).
bool is_pow2_plus1(int n) { return n >= 2 && ((n - 1) & (n - 2)) == 0; }

Terrain pad_to_pow2_plus1(const Terrain& t) {
    const int size = next_pow2_plus1(std::max(t.rows(), t.cols()));
    Terrain out(size, size, t.h_scale(), t.v_scale(), t.y_offset());
    for (int i = 0; i < size; ++i) {
        const int si = std::min(i, t.rows() - 1);
        for (int j = 0; j < size; ++j) {
            const int sj = std::min(j, t.cols() - 1);
            out.raw(i, j) = t.raw(si, sj);
            Rgb8 c = t.color(si, sj);
            if (si != i || sj != j) c = Rgb8{std::uint8_t(c.r / 2), std::uint8_t(c.g / 2), std::uint8_t(c.b / 2)};
            out.color(i, j) = c;
        }
    }
    return out;
}

} // namespace overflight
