// See TiledImagery.h. The blend and the bilinear mirror ImageryFallback.cpp
// and ImageryPyramid.cpp expression for expression, so that a tile's texels
// and colors are those of the whole pyramid.
#include "core/TiledImagery.h"

#include <glm/vec3.hpp>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <tuple>

namespace overflight {

namespace {

int floor_to_multiple(long long v, int a) {
    const long long q = v >= 0 ? v / a : -((-v + a - 1) / a);
    return int(q * a);
}

// Texels of the whole pyramid's level l along a side of n level-0 texels.
int level_side(int n, int l) {
    for (int k = 0; k < l; ++k) n = std::max(1, n / 2);
    return n;
}

int tile_side(double cells, double texel, int a) {
    // The cells' span in texels, its rounding at both ends (2), the
    // alignment of the start (a - 1) and a margin of a on each side.
    const double need = cells / texel + 2.0 + double(a - 1) + 2.0 * a;
    const double side = std::ceil(need / a) * a;
    if (!(side <= kMaxImageryTileSide))
        throw std::invalid_argument("an imagery tile would exceed " + std::to_string(kMaxImageryTileSide) + " texels a side");
    return int(side);
}

} // namespace

std::size_t ImageryTileLayout::tile_bytes() const {
    std::size_t n = 0;
    for (int m = 0; m <= levels; ++m) n += std::size_t(cols >> m) * std::size_t(rows >> m) * 4;
    return n;
}

std::size_t TileImagery::bytes() const {
    std::size_t n = 0;
    for (const Image2D<Rgba8>& l : levels) n += l.pixels.size() * sizeof(Rgba8);
    return n;
}

ImageryTileLayout plan_imagery_tiles(const TileGrid& grid, double x0, double z0, double extent_x, double extent_z,
                                     int width, int height) {
    if (!(extent_x > 0 && extent_z > 0 && std::isfinite(extent_x) && std::isfinite(extent_z) && std::isfinite(x0) &&
          std::isfinite(z0)))
        throw std::invalid_argument("imagery extent is not a positive finite size");
    if (width < 1 || height < 1) throw std::invalid_argument("imagery has no texels");
    ImageryTileLayout l;
    l.x0 = x0;
    l.z0 = z0;
    l.extent_x = extent_x;
    l.extent_z = extent_z;
    l.width = width;
    l.height = height;
    const double hs = grid.h_scale, texel = std::max(l.texel_x(), l.texel_z());
    // The first level whose texels are at least a DEM cell.
    const double ratio = hs / texel;
    l.levels = std::clamp(int(std::ceil(std::log2(std::max(ratio, 1.0)) - 1e-9)), 1, 8);
    const int a = 1 << l.levels;
    const double cells = double(grid.stride() + 1) * hs;
    l.cols = tile_side(cells, l.texel_x(), a);
    l.rows = tile_side(cells, l.texel_z(), a);
    return l;
}

std::pair<int, int> imagery_tile_origin(const ImageryTileLayout& l, const TileGrid& g, int r, int c) {
    const int a = 1 << l.levels;
    const double hs = g.h_scale, s = g.stride();
    const double u = std::floor(((double(c) * s - 0.5) * hs - l.x0) / l.texel_x());
    const double v = std::floor(((double(r) * s - 0.5) * hs - l.z0) / l.texel_z());
    return {floor_to_multiple((long long)u, a) - a, floor_to_multiple((long long)v, a) - a};
}

std::vector<Image2D<Rgba8>> imagery_tile_levels(Image2D<Rgba8> level0, int levels) {
    std::vector<Image2D<Rgba8>> out;
    out.push_back(std::move(level0));
    for (int m = 1; m <= levels; ++m) out.push_back(box_filter_half(out.back()));
    return out;
}

TileImagery cut_tile_imagery(const ImageryPyramid& whole, const ImageryTileLayout& l, const TileGrid& g, int r, int c) {
    const Image2D<Rgba8>& src = whole.level(0);
    TileImagery t;
    t.r = r;
    t.c = c;
    std::tie(t.u0, t.v0) = imagery_tile_origin(l, g, r, c);
    Image2D<Rgba8> level0(l.cols, l.rows);
    for (int i = 0; i < l.rows; ++i) {
        const int gv = std::clamp(t.v0 + i, 0, src.height - 1);
        for (int j = 0; j < l.cols; ++j) level0.at(j, i) = src.at(std::clamp(t.u0 + j, 0, src.width - 1), gv);
    }
    t.levels = imagery_tile_levels(std::move(level0), l.levels);
    return t;
}

Rgba8 tile_imagery_bilinear(const TileImagery& tile, const ImageryTileLayout& layout, double x, double z, int l) {
    const int wl = level_side(layout.width, l), hl = level_side(layout.height, l);
    const double tx = layout.extent_x / double(wl), tz = layout.extent_z / double(hl);
    const double u = std::clamp((x - layout.x0) / tx - 0.5, 0.0, double(wl - 1));
    const double v = std::clamp((z - layout.z0) / tz - 0.5, 0.0, double(hl - 1));
    const int c0 = int(u), r0 = int(v);
    const int c1 = std::min(c0 + 1, wl - 1), r1 = std::min(r0 + 1, hl - 1);
    const double fu = u - c0, fv = v - r0;
    const Image2D<Rgba8>& img = tile.levels[std::size_t(l)];
    // Texel k of the whole level l is texel k - (u0 >> l) of the tile's.
    const auto at = [&](int col, int row) {
        return img.at(std::clamp(col - (tile.u0 >> l), 0, img.width - 1), std::clamp(row - (tile.v0 >> l), 0, img.height - 1));
    };
    const Rgba8 p[4] = {at(c0, r0), at(c1, r0), at(c0, r1), at(c1, r1)};
    auto mix = [&](auto channel) {
        const double top = channel(p[0]) * (1 - fu) + channel(p[1]) * fu;
        const double bottom = channel(p[2]) * (1 - fu) + channel(p[3]) * fu;
        return std::uint8_t(std::lround(top * (1 - fv) + bottom * fv));
    };
    return Rgba8{mix([](Rgba8 t) { return double(t.r); }), mix([](Rgba8 t) { return double(t.g); }),
                 mix([](Rgba8 t) { return double(t.b); }), mix([](Rgba8 t) { return double(t.a); })};
}

int tile_sample_color_level(const ImageryTileLayout& layout, double h_scale) {
    int whole_levels = 1;
    for (int w = layout.width, h = layout.height; w > 1 || h > 1; ++whole_levels) {
        w = std::max(1, w / 2);
        h = std::max(1, h / 2);
    }
    const double texel = std::max(layout.texel_x(), layout.texel_z());
    return std::min(mip_level_for_footprint(h_scale, texel, whole_levels), layout.levels);
}

Image2D<Rgba8> blend_imagery_window(const Image2D<Rgba8>& window, const ImageryTileLayout& layout, int u0, int v0,
                                    int f, const FallbackWindow& fb) {
    const Terrain& t = *fb.samples;
    const auto in = [&](int gu, int gv) -> const Rgba8& { return window.at(gu - (u0 - f), gv - (v0 - f)); };
    // The whole terrain's color bilinear at (x, z), clamped to the whole
    // grid (ImageryFallback.cpp terrain_color), read from the window.
    const auto terrain_color = [&](double x, double z) {
        const double u = std::clamp(x / t.h_scale(), 0.0, double(fb.cols - 1));
        const double v = std::clamp(z / t.h_scale(), 0.0, double(fb.rows - 1));
        const int c0 = std::min(int(u), fb.cols - 2), r0 = std::min(int(v), fb.rows - 2);
        const float fu = float(u - c0), fv = float(v - r0);
        auto rgb = [&](int r, int c) {
            const Rgb8 p = t.color(std::clamp(r - fb.row0, 0, t.rows() - 1), std::clamp(c - fb.col0, 0, t.cols() - 1));
            return glm::vec3(p.r, p.g, p.b);
        };
        return (rgb(r0, c0) * (1 - fu) + rgb(r0, c0 + 1) * fu) * (1 - fv) +
               (rgb(r0 + 1, c0) * (1 - fu) + rgb(r0 + 1, c0 + 1) * fu) * fv;
    };
    const double tx = layout.texel_x(), tz = layout.texel_z();
    Image2D<Rgba8> out(layout.cols, layout.rows);
    for (int i = 0; i < layout.rows; ++i) {
        const int gv = v0 + i;
        if (gv < 0 || gv >= layout.height) continue;
        const int r0 = std::max(gv - f, 0), r1 = std::min(gv + f + 1, layout.height);
        for (int j = 0; j < layout.cols; ++j) {
            const int gu = u0 + j;
            if (gu < 0 || gu >= layout.width) continue;
            Rgba8 texel = in(gu, gv);
            const int c0 = std::max(gu - f, 0), c1 = std::min(gu + f + 1, layout.width);
            long long box = 0;
            for (int r = r0; r < r1; ++r)
                for (int c = c0; c < c1; ++c) box += in(c, r).a;
            const double mean = double(box) / double((r1 - r0) * (c1 - c0));
            const float w = float(std::min(double(texel.a), mean) / 255.0);
            if (w < 1.0f) {
                const glm::vec3 fc = terrain_color(layout.x0 + (gu + 0.5) * tx, layout.z0 + (gv + 0.5) * tz);
                auto mix = [&](std::uint8_t a, float b) { return std::uint8_t(std::lround(float(a) * w + b * (1.0f - w))); };
                texel.r = mix(texel.r, fc.r);
                texel.g = mix(texel.g, fc.g);
                texel.b = mix(texel.b, fc.b);
            }
            out.at(j, i) = texel;
        }
    }
    // Beyond the grid: its nearest texel, which this tile holds.
    for (int i = 0; i < layout.rows; ++i)
        for (int j = 0; j < layout.cols; ++j) {
            const int gu = u0 + j, gv = v0 + i;
            if (gu >= 0 && gu < layout.width && gv >= 0 && gv < layout.height) continue;
            out.at(j, i) = out.at(std::clamp(gu, 0, layout.width - 1) - u0, std::clamp(gv, 0, layout.height - 1) - v0);
        }
    return out;
}

} // namespace overflight
