#pragma once
// The table of terrain methods that `render`, `bench` and `fly` all read. A
// new method is one file (a TerrainMethod and its make_ function) plus one row
// in MethodTable.cpp; every command then offers it.
#include "core/SharedSunShadow.h"
#include "core/Terrain.h"
#include "methods/MethodSettings.h"
#include "methods/TerrainMethod.h"

#include <functional>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

namespace overflight {

// What a method is built from.
struct MethodContext {
    const Terrain& terrain;          // must outlive the method
    const MethodSettings& settings;  // validated
    // The quadtree's tiles when the terrain stands for a tile directory read
    // lazily (set by the command, which owns files); empty: tiles are cut from
    // `terrain` on demand.
    std::function<std::unique_ptr<TileSet>()> tiles;
    // The terrain's sun shadow shared with the compositor that draws the
    // method's images (one sweep per sun direction for both); null: the
    // method sweeps its own.
    SharedSunShadow* sun_shadow = nullptr;
};

// What `render` and `bench` do with an Images method's output (Szenberg et
// al. 1997 Table 1): nothing (the ray cast alone), present it (color upload
// and read-back), or composite the objects into it (color and depth upload,
// objects with the Z-buffer, read-back). Mesh and Resident methods are always
// drawn with the objects.
enum class Composite { None, Present, Objects };

struct MethodEntry {
    const char* name;
    const char* help;
    bool bench_by_default; // timed by `bench` without --methods
    bool fly;              // in `fly`'s Tab cycle (table order)
    Composite composite;
    // Reads a tile directory's tiles itself (MethodContext::tiles), so the
    // terrain in memory may be the directory's overview.
    bool reads_tiles;
    std::unique_ptr<TerrainMethod> (*create)(const MethodContext&); // throws Error
};

const std::vector<MethodEntry>& terrain_methods();
// The row called `name`, or nullptr.
const MethodEntry* find_terrain_method(std::string_view name);
// The names joined by `separator`; only the fly rows when `fly_only`.
std::string terrain_method_names(std::string_view separator = "|", bool fly_only = false);

} // namespace overflight
