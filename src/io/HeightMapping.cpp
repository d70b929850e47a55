// Based on: DESIGN sec. 4 (float or negative DEMs map to 16 bits with the
// mapping recorded); CMSC 23700 project 2a sec. 6.2 (16-bit height field with a vertical scale).
#include "io/HeightMapping.h"

#include <algorithm>
#include <cmath>

namespace overflight {

HeightMapping choose_height_mapping(double min, double max, bool integral) {
    if (integral && min >= 0 && max <= 65535) return {1.0f, 0.0f};
    if (integral && max - min <= 65535) return {1.0f, float(min)};
    if (!(max > min)) return {1.0f, float(min)};
    // The float v_scale may round below the exact quotient; nudge it up so the
    // maximum still lands on or below 65535 rather than being clamped.
    float vs = float((max - min) / 65535.0);
    while (double(vs) * 65535.0 < max - min) vs = std::nextafter(vs, INFINITY);
    return {vs, float(min)};
}

void quantise_heights(const std::vector<float>& elevations, HeightMapping mapping, std::vector<std::uint16_t>& out) {
    out.resize(elevations.size());
    const double inv = 1.0 / double(mapping.v_scale);
    for (std::size_t i = 0; i < elevations.size(); ++i) {
        const double h = std::round((double(elevations[i]) - double(mapping.y_offset)) * inv);
        out[i] = std::uint16_t(std::clamp(h, 0.0, 65535.0));
    }
}

std::pair<float, float> mapped_range(HeightMapping mapping, float lo, float hi) {
    std::vector<std::uint16_t> ends;
    quantise_heights({lo, hi}, mapping, ends);
    return {mapping.v_scale * float(ends[0]) + mapping.y_offset, mapping.v_scale * float(ends[1]) + mapping.y_offset};
}

} // namespace overflight
