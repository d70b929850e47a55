#pragma once
// The terrain methods of `overflight fly` (issue 7), in Tab order, all drawing
// the same chase camera (DESIGN sec. 2) so that switching keeps the view:
//
//   mesh      the full-resolution triangulation (TerrainMesh), frustum-culled
//             chunks: the Z-buffer baseline (Szenberg sec. 7).
//   voxel     the Floating Horizon ray cast of every frame on the CPU
//             (raycast/FloatingHorizon, Szenberg sec. 4-6), its color and
//             window depth uploaded through pixel buffers and written into the
//             target by a full-screen depth-writing pass (Szenberg sec. 5,
//             Fig. 5), so the objects drawn next are composited by depth.
//   roam      split-only ROAM (lod/RoamMesh, seed 003 sec. 5) tessellated every
//             frame with the vehicle as focus; + / _ scale the triangle budget
//             by sqrt 2 (default 65536).
//   quadtree  Röttger's quadtree over overlapping 257^2 tiles cut from the
//             terrain, or over a tile directory's tiles (lod/TileSet, Zamri
//             seed 001); + / _ divide / multiply the screen-space error by
//             sqrt 2 (default 1 px).
//
// Each factory needs a current GL 4.5 context; `data` must outlive the method.
#include "core/DataSet.h"
#include "gl/FlightMethod.h"
#include "lod/TileSet.h"

#include <memory>
#include <string>
#include <vector>

namespace overflight::gl {

std::unique_ptr<FlightMethod> make_mesh_flight_method(const DataSet& data);
std::unique_ptr<FlightMethod> make_voxel_flight_method(const DataSet& data);
std::unique_ptr<FlightMethod> make_roam_flight_method(const DataSet& data);
std::unique_ptr<FlightMethod> make_quadtree_flight_method(const DataSet& data);
// The quadtree over tiles from elsewhere (a tile directory read lazily: `fly DIR`).
std::unique_ptr<FlightMethod> make_quadtree_flight_method(std::unique_ptr<TileSet> tiles);

// "mesh", "voxel", "roam", "quadtree": the Tab order.
const std::vector<std::string>& flight_method_names();
// The method called `name`, or nullptr for a name not in flight_method_names().
std::unique_ptr<FlightMethod> make_flight_method(const std::string& name, const DataSet& data);

} // namespace overflight::gl
