#pragma once
// The one interface every terrain method implements, whichever command shows
// it (`render`, `bench`, `fly`) and whichever renderer composites it: given
// the shared camera (DESIGN sec. 2), a method produces either
//
//   Images    a color image and an OpenGL window-depth image (1.0 = sky), as
//             the ray casters do (Szenberg, Gattass, Carvalho, "An Algorithm
//             for the Visualization of a Terrain with Objects", SIBGRAPI 1997,
//             sec. 5: the terrain image composited with Z-buffered objects);
//   Mesh      plain vertex / index arrays rebuilt for the frame, as the LOD
//             methods do (split-only ROAM, Röttger's quadtree over tiles), which
//             a renderer only uploads and draws (Strugar's CDLOD split of
//             selection and drawing);
//   Resident  one of the full-resolution Z-buffer representations of the
//             terrain's samples (the full mesh and Szenberg's Table 2 block
//             representations), which a renderer uploads once and draws
//             every frame: the method only names it.
//
// No GL and no files here: methods are tested without a GPU, and the GL
// compositor (gl/Compositor.h) takes any MethodOutput.
#include "core/Camera.h"
#include "core/DataSet.h"
#include "core/Image.h"
#include "core/MeshArrays.h"
#include "lod/RoamMesh.h"
#include "lod/TileSet.h"
#include "raycast/RaycastOptions.h"

#include <glm/vec2.hpp>

#include <chrono>
#include <optional>
#include <string>
#include <vector>

namespace overflight {

enum class MethodOutputKind { Images, Mesh, Resident };

// The resident representations (Szenberg et al. 1997 sec. 3, Table 2 (a)-(e),
// and the full-resolution mesh of DESIGN sec. 3).
enum class ResidentSurface { Mesh, Points, TopFaces, FrontFaces, Segments, Blocks };
const char* to_string(ResidentSurface s);

// One frame's product; the pointers stay valid until the method's next produce().
struct MethodOutput {
    MethodOutputKind kind = MethodOutputKind::Images;
    const ColorImage* color = nullptr; // Images: row 0 at the top
    const DepthImage* depth = nullptr; // Images: window depth for the camera's near/far
    const MeshArrays* mesh = nullptr;  // Mesh: world coordinates
    ResidentSurface surface = ResidentSurface::Mesh; // Resident
    const TileImageryFrame* tile_imagery = nullptr;   // Mesh: the imagery tiles it shows (quadtree over tiles)

    static MethodOutput images(const ColorImage& color, const DepthImage& depth);
    static MethodOutput of_mesh(const MeshArrays& mesh);
    static MethodOutput resident(ResidentSurface surface);
};

// What a method sees of a frame.
struct MethodView {
    const Camera& camera;           // validated by the method
    const Environment& environment; // fog and sky (the ray casters paint them)
    std::optional<glm::dvec2> focus; // world (x, z) of a vehicle, if one is flying
};

// A timed step of a method's CPU work (names are string literals).
struct MethodStep {
    const char* name = "";
    double ms = 0;
};

// What one frame cost and produced, typed: the commands format it (--stats,
// bench rows, the fly HUD). Fields a method does not fill stay empty.
struct MethodStats {
    std::vector<MethodStep> steps;        // CPU steps in order (the renderer adds its GL steps)
    long long triangles = 0;              // Mesh: triangles produced
    std::optional<RaycastStats> raycast;  // the Floating Horizon and its literal reference
    long long rays = 0;                   // the ray marcher: rays traced
    std::optional<RoamStats> roam;
    std::optional<TileFrameStats> tiles;  // the quadtree over tiles
    // Clears the frame's figures; keeps the steps' storage (no allocation per frame).
    void clear();
    // Adds the step `name` (a string literal) lasting from `start` to now.
    void add_step_since(const char* name, std::chrono::steady_clock::time_point start);
    double step_ms(const char* name) const; // 0 when absent
};

class TerrainMethod {
public:
    virtual ~TerrainMethod() = default;
    virtual MethodOutputKind output_kind() const = 0;
    // Produces the frame for view.camera; fills `stats` (cleared first).
    // Throws Error("camera", ...) for an invalid camera.
    virtual MethodOutput produce(const MethodView& view, MethodStats& stats) = 0;
    // Images methods that render every pixel of their images each frame may
    // lend them: swaps the color image of the last produce() with `color`, and
    // the depth image with `*depth` when `depth` is not null, so that a caller
    // keeps the frame without copying it (the Python module hands it to NumPy).
    // What the method receives may hold anything of any size: the next
    // produce() renders over it. Returns false, swapping nothing, when the
    // method cannot (the default): the caller copies out of MethodOutput.
    virtual bool swap_images(ColorImage& /*color*/, DepthImage* /*depth*/) { return false; }
    // The level-of-detail knob, multiplied by `factor` (> 1: finer: a larger
    // triangle budget or a smaller screen-space error). No-op without one.
    virtual void scale_detail(double /*factor*/) {}
    // The knob's current value for a HUD ("budget 65536", "error 1.00 px"); "" if none.
    virtual std::string detail() const { return {}; }
};

} // namespace overflight
