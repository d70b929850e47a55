#pragma once
// The knobs of the terrain methods beyond the camera, with their defaults in
// this one place (every command and the fly window start from these).
#include "raycast/RaycastOptions.h"

#include <cstddef>

namespace overflight {

struct MethodSettings {
    static constexpr int kDefaultTriangles = 65536;        // ROAM's triangle budget per frame
    static constexpr int kMinTriangles = 2, kMaxTriangles = 1 << 24;
    static constexpr double kDefaultErrorPx = 1.0;         // Röttger's screen-space error target
    static constexpr double kMinErrorPx = 0.01, kMaxErrorPx = 1000.0;
    static constexpr int kDefaultCacheMib = 1024;          // loaded tiles of the quadtree
    static constexpr int kMaxCacheMib = 1 << 24;
    static constexpr int kDefaultTileSize = 257;           // tiles cut from a terrain in memory

    RaycastOptions raycast;                 // voxel, voxel-literal, raymarch
    int triangles = kDefaultTriangles;      // roam
    double error_px = kDefaultErrorPx;      // quadtree
    std::size_t cache_bytes = std::size_t(kDefaultCacheMib) << 20; // quadtree
    int tile_size = kDefaultTileSize;       // quadtree over a terrain in memory

    // Checks every knob; throws Error in the algorithms' own terms, e.g.
    // Error("triangle budget", "0 is below 2"), Error("screen-space error", ...),
    // Error("tile cache", ...), Error("near step", ...). Commands map the
    // subject to the option that set it (method_option_for).
    void validate() const;
};

// A tile cache bound in MiB, as bytes; throws Error("tile cache", ...) outside 1..2^24 MiB.
std::size_t tile_cache_bytes(long long cache_mib);

} // namespace overflight
