// Based on: Szenberg, Gattass, Carvalho, "An Algorithm for the Visualization of
// a Terrain with Objects" (SIBGRAPI 1997), Tables 1 and 2; Röttger et al.,
// "Real-Time Generation of Continuous Levels of Detail for Height Fields"
// (1998); Duchaineau et al., "ROAMing Terrain" (1997), split-only as in the
// CMSC 23700 hovercraft project, sec. 5.
#include "methods/MethodTable.h"

namespace overflight {

// One line per method file.
std::unique_ptr<TerrainMethod> make_voxel_method(const MethodContext&);
std::unique_ptr<TerrainMethod> make_voxel_literal_method(const MethodContext&);
std::unique_ptr<TerrainMethod> make_resident_mesh_method(const MethodContext&);
std::unique_ptr<TerrainMethod> make_points_method(const MethodContext&);
std::unique_ptr<TerrainMethod> make_top_faces_method(const MethodContext&);
std::unique_ptr<TerrainMethod> make_front_faces_method(const MethodContext&);
std::unique_ptr<TerrainMethod> make_segments_method(const MethodContext&);
std::unique_ptr<TerrainMethod> make_blocks_method(const MethodContext&);
std::unique_ptr<TerrainMethod> make_roam_method(const MethodContext&);
std::unique_ptr<TerrainMethod> make_quadtree_method(const MethodContext&);
std::unique_ptr<TerrainMethod> make_raymarch_method(const MethodContext&);

const std::vector<MethodEntry>& terrain_methods() {
    using C = Composite;
    // name, help, bench by default, in fly, composite (Images only), reads tiles, factory
    static const std::vector<MethodEntry> table = {
        {"mesh", "full-resolution triangle mesh, OpenGL Z-buffer (the baseline)", true, true, C::Objects, false,
         make_resident_mesh_method},
        {"voxel", "Floating Horizon ray caster (Szenberg 1997), parallel, exact", true, true, C::None, false,
         make_voxel_method},
        {"voxel+present", "ray cast + color upload + present (Szenberg Table 1, without objects)", true, false,
         C::Present, false, make_voxel_method},
        {"voxel+objects", "ray cast + color and depth upload + Z-buffered objects (Szenberg Table 1, Fig. 5)", true,
         false, C::Objects, false, make_voxel_method},
        {"voxel-literal", "Szenberg's Algorithm 1 as printed, single-threaded (reference, shear only)", true, false,
         C::None, false, make_voxel_literal_method},
        {"points", "Szenberg Table 2 (a): a point on each top face", true, false, C::Objects, false, make_points_method},
        {"top-faces", "Szenberg Table 2 (b): the top face of each block", true, false, C::Objects, false,
         make_top_faces_method},
        {"front-faces", "Szenberg Table 2 (c): top and frontal faces", true, false, C::Objects, false,
         make_front_faces_method},
        {"segments", "Szenberg Table 2 (d): straight line segments", true, false, C::Objects, false, make_segments_method},
        {"blocks", "Szenberg Table 2 (e): whole blocks", true, false, C::Objects, false, make_blocks_method},
        {"roam", "split-only ROAM, --triangles budget (CMSC 23700 hovercraft project sec. 5)", true, true, C::Objects, false,
         make_roam_method},
        {"quadtree", "Roettger quadtree over overlapping tiles, --error pixels (Zamri)", true, true, C::Objects, true,
         make_quadtree_method},
        {"raymarch", "brute-force per-pixel ray marcher (reference)", false, false, C::None, false, make_raymarch_method},
    };
    return table;
}

const MethodEntry* find_terrain_method(std::string_view name) {
    for (const MethodEntry& m : terrain_methods())
        if (name == m.name) return &m;
    return nullptr;
}

std::string terrain_method_names(std::string_view separator, bool fly_only) {
    std::string names;
    for (const MethodEntry& m : terrain_methods()) {
        if (fly_only && !m.fly) continue;
        if (!names.empty()) names += separator;
        names += m.name;
    }
    return names;
}

} // namespace overflight
