#pragma once
// How elevations in metres become the 16-bit samples of a Terrain (DESIGN
// sec. 1 and 4): Y = v_scale * H + y_offset. Integer elevations that fit keep
// v_scale = 1 (exact); float or out-of-range elevations are spread over the
// whole 16-bit range, v_scale = (max - min) / 65535 and y_offset = min, so the
// quantisation error is at most half a step, v_scale / 2.
#include <cstdint>
#include <utility>
#include <vector>

namespace overflight {

struct HeightMapping {
    float v_scale = 1.0f;
    float y_offset = 0.0f;
};

// `integral`: every elevation is a whole number of metres. Non-negative whole
// elevations up to 65535 map with y_offset = 0 (as hovercraft data); other whole
// elevations spanning at most 65535 keep v_scale = 1 with y_offset = min; a
// constant field gets v_scale = 1, y_offset = min.
HeightMapping choose_height_mapping(double min, double max, bool integral);

// The world heights (v_scale * H + y_offset) of the 16-bit samples nearest
// to elevations lo and hi under `mapping`: the ends of the elevation ramp of
// a terrain whose elevations span [lo, hi].
std::pair<float, float> mapped_range(HeightMapping mapping, float lo, float hi);

// Nearest 16-bit sample of each elevation under `mapping` (clamped to 0..65535).
void quantise_heights(const std::vector<float>& elevations, HeightMapping mapping, std::vector<std::uint16_t>& out);

} // namespace overflight
