#pragma once
// The one compositor of every terrain method (methods/TerrainMethod.h), used by
// headless rendering (`render`, `bench`, replays) and by the `fly` window
// alike: it takes what a method produced for the shared camera, uploads it,
// draws it with the sky, then draws the objects (and a vehicle) with the
// Z-buffer, so that they land on the same pixels whichever method drew the
// ground (Szenberg et al. 1997 sec. 5, Fig. 5).
//
//   Images    the color image is loaded into an offscreen target
//             ("color_upload"); with objects its window depth too
//             ("depth_upload"), only where objects, the vehicle or the
//             objects' shadows can be drawn (depth_rect(), the whole image
//             when it is read back), the sky rows of that rectangle cleared
//             without a transfer. The loads go through the persistently
//             mapped slots of an ImageStream, whose CPU copy (stage()) may run
//             on another thread ahead of the GL thread (the `fly` window casts
//             and stages frame N+1 while frame N is drawn); the color is
//             staged in the texture's own byte order, so its load is a copy.
//             A window receives the finished composite's color by a blit
//             ("blit"): no full-screen pass, no depth written; its composites
//             alternate between two offscreen targets, so loading frame N+1
//             never waits for GL to finish drawing frame N. The ray cast
//             paints its own sky.
//   Mesh      depth cleared and the sky drawn ("sky"), the arrays streamed to
//             GL ("upload") and drawn lit and fogged ("terrain").
//   Resident  depth cleared, sky, the representation uploaded on first use
//             (outside any timed step) and drawn ("terrain").
// Mesh and Resident then get Environment::water's surface (gl/WaterPlane.h,
// "water"); the ray casters paint their own (raycast/WaterPass.h).
// Then "objects": the scene's objects and the vehicle, depth-tested.
//
// With Environment::shadows the terrain's shadow ceiling for the sun
// (core/HorizonSweep.h) is swept when the sun moves ("shadow_sweep") and
// uploaded as a texture, so that the mesh methods' terrain and every
// method's objects receive the terrain's cast shadows in shade(); the
// objects cast theirs onto the terrain and each other through a shadow map
// from the sun (ObjectShadowMap, rendered when the sun moves), read in
// shade() and, on the ray casters' images, by ShadowScreenPass
// ("object_shadows") over the pixels core/ShadowPixels.h finds on the CPU
// from the image's depth ("shadow_reach" when draw() works it out; stage()
// does it on the staging thread, untimed). The vehicle casts its shadow the same way through a
// second map fitted to it alone, rendered whenever it moved.
//
// Fog used by every program (the ray caster matches it, raycast/Atmosphere.h):
//     f = exp(-fog_density * d),  d = |P - eye| (eye-space distance),
//     color = mix(fog_color, lit, f),  lit = albedo * (ambient + sun_color * max(N.sun_dir, 0) * visible),
// visible = 0 below the terrain's shadow ceiling (with shadows on), else 1;
// with Environment::atmosphere, the aerial perspective and sky of
// core/AerialPerspective.h instead of the fog (GLSL aerial(), air_sky()).
//
// Based on: Szenberg, Gattass, Carvalho, "An Algorithm for the Visualization of
// a Terrain with Objects" (SIBGRAPI 1997), sec. 3, 5 and 7 (Tables 1 and 2);
// CMSC 23700 hovercraft project sec. 3-4 (vehicle, sun, fog, sky).
#include "core/Camera.h"
#include "core/DataSet.h"
#include "core/HeightBounds.h"
#include "core/SharedSunShadow.h"
#include "gl/BlockTerrain.h"
#include "gl/FlightVehicle.h"
#include "gl/FrameUniforms.h"
#include "gl/ObjectRenderer.h"
#include "gl/ObjectShadowMap.h"
#include "gl/RenderTarget.h"
#include "gl/ImageStream.h"
#include "gl/ImageryTexture.h"
#include "gl/TiledImageryTexture.h"
#include "gl/ShadowCeilingTexture.h"
#include "gl/ShadowScreenPass.h"
#include "gl/SkyPass.h"
#include "gl/StepTimer.h"
#include "gl/StreamedMesh.h"
#include "gl/TerrainMesh.h"
#include "gl/WaterPlane.h"
#include "methods/TerrainMethod.h"

#include <array>
#include <memory>
#include <optional>
#include <vector>

namespace overflight::gl {

// Where the hovercraft is, if one is drawn (DESIGN sec. 1 heading).
struct VehiclePose {
    double x = 0, z = 0, heading = 0;
};

struct CompositeOptions {
    bool objects = true;    // Images: false loads the color alone (Szenberg Table 1 "without objects")
    bool full_depth = false; // Images, offscreen: load every pixel's depth (the caller reads it back)
    bool wireframe = false;  // Mesh and Resident
    std::optional<VehiclePose> vehicle;
};

struct CompositeCounts {
    long long terrain_primitives = 0; // triangles (points, lines for those representations)
    long long object_triangles = 0;   // scene objects and the vehicle
    int chunks_total = 0, chunks_drawn = 0; // the resident mesh's frustum-culled chunks
};

class Compositor {
public:
    // Uploads the scene's objects on `terrain` (which must outlive this). A
    // GL 4.5 context must be current.
    Compositor(const Terrain& terrain, const Scene& scene);

    // Draws one frame of `out` for `camera` (validated; its size must be the
    // target's) into `target`, which is bound here. Throws Error("camera", ...).
    CompositeCounts draw(const MethodOutput& out, const Camera& camera, const Environment& environment,
                         RenderTarget& target, StepTimer& timer, const CompositeOptions& options);

    // Takes the terrain's shadow ceiling from `shared` (which must outlive
    // this), swept once per sun direction for this compositor and the ray
    // casters whose images it draws (MethodContext::sun_shadow), rather than
    // sweeping its own. Null: its own again.
    void share_sun_shadow(SharedSunShadow* shared) {
        shared_shadow_ = shared;
        shadow_valid_ = false;
    }

    // Uploads a resident representation now (draw() does it on first use).
    void prepare(ResidentSurface surface);

    // The pipelined composite of an Images output, in three steps (draw()
    // does all three in one go): acquire_slot() on the GL thread gives a slot
    // of the image stream, for the camera's size, that GL no longer reads;
    // stage() copies the output into it (no GL: any thread, one stage per
    // slot at a time, while the GL thread may draw from another slot);
    // draw_staged() on the GL thread then draws the frame from the slot like
    // draw(), with the same camera, environment and options as stage().
    int acquire_slot(const Camera& camera);
    void stage(int slot, const MethodOutput& out, const Camera& camera, const Environment& environment,
               const CompositeOptions& options);
    CompositeCounts draw_staged(int slot, const Camera& camera, const Environment& environment, RenderTarget& target,
                                StepTimer& timer, const CompositeOptions& options);

    // The pixels of an Images composite whose depth is loaded: the objects'
    // screen rectangle, the vehicle's, and the reach of the objects' shadows
    // when the shadow pass runs; the whole image with options.full_depth.
    // No GL: any thread.
    PixelRect depth_rect(const Camera& camera, const Environment& environment, const CompositeOptions& options) const;

    const ObjectRenderer& objects() const { return objects_; }
    WaterPlane& water() { return water_; }

private:
    void begin(const Camera& camera, const Environment& environment, const RenderTarget& target, StepTimer& timer,
               const CompositeOptions& options);
    // The shadow vector of the frame block for `environment` (sweeps and uploads when the sun moved).
    glm::vec4 terrain_shadow(const Environment& environment, StepTimer& timer);
    CompositeCounts compose(const MethodOutput* out, int slot, const Camera& camera, const Environment& environment,
                            RenderTarget& target, StepTimer& timer, const CompositeOptions& options);
    // Where the objects' shadow pass darkens a ray-cast image, worked out
    // once per frame (by stage() for its slot, or by draw()).
    struct ShadowReach {
        std::vector<PixelRect> rects; // the pixels the pass covers, as disjoint rectangles; none: no pass
        PixelRect rect;               // their bounding rectangle
    };
    // Loads the images (staged now from `out` when given, else from `slot`) into `into`.
    void draw_images(const MethodOutput* out, int slot, const Camera& camera, const ShadowReach& reach,
                     RenderTarget& into, StepTimer& timer, const CompositeOptions& options);
    // Fills `reach` for a frame (nothing when the pass does not run): with
    // the ray caster's `depth`, the pixels whose points may lie in a shadow
    // (core/ShadowPixels.h); without, each caster's screen rectangle.
    void object_shadow_reach(const Camera& camera, const Environment& environment, const CompositeOptions& options,
                             const DepthImage* depth, ShadowReach& reach) const;
    PixelRect depth_rect(const Camera& camera, const CompositeOptions& options, const PixelRect& shadow_rect) const;
    // A height below every terrain sample under `box`'s footprint (from the
    // terrain's per-block minima), at least the terrain's lowest.
    float floor_under(const WorldBox& box) const;
    long long draw_surface(const MethodOutput& out, const Camera& camera, StepTimer& timer, CompositeCounts& counts);

    const Terrain& terrain_;
    static constexpr int kFloorBlock = 32; // samples per side of a block of block_min_
    int block_rows_ = 0, block_cols_ = 0;
    std::vector<float> block_min_; // the lowest sample of each block, row-major
    float terrain_min_ = 0;        // the lowest of block_min_: the terrain's lowest sample
    float object_texel_ = 0;       // ObjectShadowMap::texel_bound of the objects' map
    SnapGrid snap_;                // the samples ShadowScreenPass snaps to (ShadowCeilingTexture::grid)
    HeightBounds snap_bounds_;     // their heights' bounds (snap_.bounds when shadow_pixels is called)
    FrameUniforms frame_;
    SharedSunShadow* shared_shadow_ = nullptr; // share_sun_shadow()
    ShadowCeiling shadow_;                     // without shared_shadow_
    glm::vec3 shadow_for_{0.0f};               // the sun of the uploaded ceiling
    bool shadow_valid_ = false;
    ShadowCeilingTexture shadow_texture_;
    ObjectShadowMap object_shadow_;
    ObjectShadowMap vehicle_shadow_{ObjectShadowMap::kVehicleUnit, ObjectShadowMap::kVehicleBinding,
                                    ObjectShadowMap::kVehicleSize};
    ShadowScreenPass object_shadow_pass_;
    ImageryTexture imagery_texture_;
    TiledImageryTexture tiled_imagery_;
    SkyPass sky_;
    WaterPlane water_{terrain_};
    ObjectRenderer objects_;
    FlightVehicle vehicle_;
    StreamedMesh streamed_;
    std::unique_ptr<TerrainMesh> mesh_;
    std::unique_ptr<BlockTerrain> blocks_;
    ImageStream stream_;
    int next_slot_ = 0;
    std::array<ShadowReach, ImageStream::kSlots> staged_reach_; // stage()'s, per slot
    ShadowReach drawn_reach_;                                   // draw()'s
    std::array<std::unique_ptr<RenderTarget>, 2> images_; // a window's Images composites, in turn, blitted to it
    int next_image_ = 0;
};

} // namespace overflight::gl
