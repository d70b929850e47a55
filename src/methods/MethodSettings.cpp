#include "methods/MethodSettings.h"

#include "core/Error.h"

#include <string>

namespace overflight {

std::size_t tile_cache_bytes(long long cache_mib) {
    if (cache_mib < 1 || cache_mib > MethodSettings::kMaxCacheMib)
        throw Error("tile cache", std::to_string(cache_mib) + " MiB is outside 1..16777216 MiB");
    return std::size_t(cache_mib) << 20;
}

void MethodSettings::validate() const {
    if (triangles < kMinTriangles)
        throw Error("triangle budget", std::to_string(triangles) + " is below " + std::to_string(kMinTriangles));
    if (triangles > kMaxTriangles)
        throw Error("triangle budget", std::to_string(triangles) + " is above " + std::to_string(kMaxTriangles));
    if (!(error_px >= kMinErrorPx && error_px <= kMaxErrorPx))
        throw Error("screen-space error", "must be in 0.01..1000 pixels");
    if (cache_bytes < (std::size_t(1) << 20) || cache_bytes > (std::size_t(kMaxCacheMib) << 20))
        throw Error("tile cache", "must be in 1..16777216 MiB");
    if (!(raycast.near_step_pixels >= 0.0 && raycast.near_step_pixels <= 1000.0))
        throw Error("near step", "must be in 0..1000 pixels");
}

} // namespace overflight
