// Based on: Szenberg et al. 1997 sec. 5 (any terrain renderer composited with
// the same Z-buffered objects); issue 7 (Tab cycles the methods).
#include "gl/FlightMethods.h"

namespace overflight::gl {

const std::vector<std::string>& flight_method_names() {
    static const std::vector<std::string> names = {"mesh", "voxel", "roam", "quadtree"};
    return names;
}

std::unique_ptr<FlightMethod> make_flight_method(const std::string& name, const DataSet& data) {
    if (name == "mesh") return make_mesh_flight_method(data);
    if (name == "voxel") return make_voxel_flight_method(data);
    if (name == "roam") return make_roam_flight_method(data);
    if (name == "quadtree") return make_quadtree_flight_method(data);
    return nullptr;
}

} // namespace overflight::gl
