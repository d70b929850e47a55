#pragma once
// The built-in `demo` terrain (DESIGN sec. 4): a deterministic procedural
// island, so the program runs on a fresh machine with no data. Fractal relief
// (ridged multifractal noise) shaped by a radial falloff into an island with
// a coast, colored beach/grass/forest/rock/snow with baked shading, with a few
// houses, a vehicle and a transmission line in its scene.
#include "core/DataSet.h"

#include <cstdint>

namespace overflight {

struct DemoOptions {
    int size = 1025;          // samples per side, 2^n+1 in 33..16385
    std::uint32_t seed = 1997; // same seed, same island, on every machine
    float h_scale = 10.0f;    // metres between samples
};

// Throws Error("demo", ...) for a size that is not 2^n+1 in 33..16385.
DataSet make_demo_island(const DemoOptions& options = {});

} // namespace overflight
