#pragma once
// The terrain model of DESIGN sec. 1: a height field of 16-bit samples with a
// horizontal scale, a vertical scale and a vertical offset, plus one RGB color
// per sample. Sample (row i, col j) is the world point
//     X = hs * j,  Y = vs * H[i][j] + y0,  Z = hs * i
// (X east, Y up, Z south). No GL, no file I/O: loaders in src/io build it.
#include "core/Image.h"

#include <glm/vec3.hpp>

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace overflight {

class ImageryPyramid;

class Terrain {
public:
    Terrain() = default;
    // Heights default to 0 and colors to mid grey. Throws Error("terrain", ...)
    // for sizes < 2 or > 65537, a horizontal_scale_problem, or a v_scale or
    // y_offset that is not finite; loaders check their input first, so that
    // their errors name the file.
    Terrain(int rows, int cols, float h_scale, float v_scale = 1.0f, float y_offset = 0.0f);

    int rows() const { return rows_; }
    int cols() const { return cols_; }
    float h_scale() const { return h_scale_; }
    float v_scale() const { return v_scale_; }
    float y_offset() const { return y_offset_; }

    // Raw samples, row-major, rows()*cols().
    std::vector<std::uint16_t>& heights() { return heights_; }
    const std::vector<std::uint16_t>& heights() const { return heights_; }
    // One color per sample, row-major (color maps per grid cell are normalised by the loaders).
    std::vector<Rgb8>& colors() { return colors_; }
    const std::vector<Rgb8>& colors() const { return colors_; }

    // An orthophoto finer than the samples (core/ImageryPyramid.h), shared by
    // copies, or null; colors() then hold it averaged to one color per sample.
    const ImageryPyramid* imagery() const { return imagery_.get(); }
    const std::shared_ptr<const ImageryPyramid>& imagery_ptr() const { return imagery_; }
    void set_imagery(std::shared_ptr<const ImageryPyramid> imagery) { imagery_ = std::move(imagery); }

    std::uint16_t raw(int row, int col) const { return heights_[index(row, col)]; }
    std::uint16_t& raw(int row, int col) { return heights_[index(row, col)]; }
    Rgb8 color(int row, int col) const { return colors_[index(row, col)]; }
    Rgb8& color(int row, int col) { return colors_[index(row, col)]; }
    std::size_t index(int row, int col) const { return std::size_t(row) * std::size_t(cols_) + std::size_t(col); }

    // World Y of a sample.
    float sample_height(int row, int col) const { return v_scale_ * float(raw(row, col)) + y_offset_; }
    // World extent: X in [0, width()], Z in [0, depth()].
    float width() const { return h_scale_ * float(cols_ - 1); }
    float depth() const { return h_scale_ * float(rows_ - 1); }
    bool contains(float x, float z) const { return x >= 0 && z >= 0 && x <= width() && z <= depth(); }

    // Surface model `blocks`: the height of the nearest sample (clamped to the grid).
    float height_nearest(float x, float z) const;
    // Surface model `bilinear`: interpolated between the four surrounding samples (clamped).
    float height_bilinear(float x, float z) const;
    // Unit surface normal of the bilinear surface at (x, z), from central differences of the samples.
    glm::vec3 normal(float x, float z) const;
    // Unit normal at a sample from central differences (one-sided at the border).
    glm::vec3 sample_normal(int row, int col) const;

    // World elevation range over all samples.
    float min_height() const;
    float max_height() const;

private:
    int rows_ = 0;
    int cols_ = 0;
    float h_scale_ = 1.0f;
    float v_scale_ = 1.0f;
    float y_offset_ = 0.0f;
    std::vector<std::uint16_t> heights_;
    std::vector<Rgb8> colors_;
    std::shared_ptr<const ImageryPyramid> imagery_;
};

// World coordinates are floats (DESIGN sec. 1). Beyond 2^24 world units a
// float no longer holds every whole unit, so neither the extent of a terrain
// nor any of its elevations may lie farther than this from the origin: such
// a height field cannot be drawn or flown over, whatever the file says.
inline constexpr double kWorldLimit = 16777216.0;

// Why rows x cols samples `h_scale` apart do not make a terrain's horizontal
// extent (h_scale not a positive number, or an extent beyond kWorldLimit), or
// an empty string when they do.
std::string horizontal_scale_problem(int rows, int cols, double h_scale);

// Why `elevation` (world units) is not a terrain height (not finite, or beyond
// kWorldLimit), or an empty string when it is one.
std::string elevation_problem(double elevation);

// Zamri's rule (Zamri, sec. 3): the smallest 2^n+1 that is >= n.
int next_pow2_plus1(int n);
bool is_pow2_plus1(int n);

// Pads to a (2^n+1)^2 square, n from next_pow2_plus1(max(rows, cols)), placing the
// source at row 0, col 0 so world coordinates do not move. Padding samples repeat
// the nearest edge sample (no cliff at the border); padded colors are darkened so
// they read as "no data" in pictures.
Terrain pad_to_pow2_plus1(const Terrain& t);

} // namespace overflight
