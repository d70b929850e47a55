#pragma once
// The terrains of the micro-benchmarks, built or loaded once per process:
// demo islands by size, and Mt Rainier from ../shared/data (a demo island
// stands in when the shared data is absent, so the benchmarks always run).
#include "core/DemoIsland.h"
#include "io/LoadTerrain.h"

#include <filesystem>
#include <map>
#include <string>

namespace overflight::bench {

inline const Terrain& demo_island(int size) {
    static std::map<int, DataSet> cache;
    auto it = cache.find(size);
    if (it == cache.end()) {
        DemoOptions o;
        o.size = size;
        it = cache.emplace(size, make_demo_island(o)).first;
    }
    return it->second.terrain;
}

inline const Terrain& rainier_or_demo(int fallback_size) {
    static const std::string srtm =
        (std::filesystem::path(__FILE__).parent_path() / ".." / ".." / "shared" / "data" / "srtm" / "mt_rainier_90m.tif")
            .string();
    if (!std::filesystem::exists(srtm)) return demo_island(fallback_size);
    static const DataSet rainier = load_terrain(srtm);
    return rainier.terrain;
}

} // namespace overflight::bench
