#pragma once
// One OpenGL renderer for every target (offscreen FBO or a GLFW window's
// default framebuffer) and every terrain method of DESIGN sec. 6 that GL
// draws: the full-resolution `mesh`, the five block representations of
// Szenberg's Table 2, meshes streamed from ROAM / quadtree / tiles, and the
// objects, all lit by the sun, fogged (GL_EXP) and over the same sky.
//
// Frame order: begin_frame() (uniforms, clear depth to 1.0, sky), one terrain
// draw, draw_objects(). For the ray caster (Szenberg sec. 5, Fig. 5) use
// begin_composite() instead, upload its color and depth into the offscreen
// target (RenderTarget::upload_color / upload_depth), then draw_objects().
//
// Fog used by every program (tell-tale for the ray caster, which must match):
//     f = exp(-fog_density * d),  d = |P - eye| (eye-space distance),
//     color = mix(fog_color, lit, f),  lit = albedo * (ambient + sun_color * max(N.sun_dir, 0)).
// Sky: SkyPass.h.
//
// Based on: Szenberg et al. 1997 sec. 3, 5, 7; DESIGN sec. 2, 3, 5.
#include "core/Camera.h"
#include "core/DataSet.h"
#include "core/MeshArrays.h"
#include "gl/BlockTerrain.h"
#include "gl/FrameUniforms.h"
#include "gl/ObjectRenderer.h"
#include "gl/RenderTarget.h"
#include "gl/SkyPass.h"
#include "gl/StreamedMesh.h"
#include "gl/TerrainMesh.h"

#include <memory>
#include <optional>
#include <string_view>

namespace overflight::gl {

// The GL-drawn terrain methods: the full mesh and the Table 2 baselines.
enum class TerrainMethod { Mesh, Points, TopFaces, FrontFaces, Segments, Blocks };

// "mesh", "points", "top-faces", "front-faces", "segments", "blocks".
std::optional<TerrainMethod> parse_terrain_method(std::string_view name);
const char* to_string(TerrainMethod m);

struct TerrainDrawStats {
    long long primitives = 0; // triangles (points / lines for those methods)
    int chunks_total = 0;     // mesh only
    int chunks_drawn = 0;
};

class Renderer {
public:
    // Keeps a reference to `data` (it must outlive the renderer). A GL 4.5
    // context must be current; GL data for a method is uploaded on first use.
    explicit Renderer(const DataSet& data);

    // Replaces the objects drawn by draw_objects() (typically data.scene plus a --scene file).
    void set_scene(const Scene& scene);

    // Binds `target`, loads the frame uniforms for `camera`, clears depth to
    // 1.0 and draws the sky. Throws Error("camera", ...) for an invalid camera.
    void begin_frame(const Camera& camera, const RenderTarget& target);
    // Binds `target` and loads the uniforms without touching its contents.
    void begin_composite(const Camera& camera, const RenderTarget& target);

    TerrainDrawStats draw_terrain(TerrainMethod method);
    // Uploads a per-frame mesh (ROAM, quadtree, tiles) and draws it like the full mesh.
    long long draw_mesh(const MeshArrays& mesh);
    long long draw_objects();

    // Uploads the GL data of a method now, so that timing a frame excludes it.
    void prepare(TerrainMethod method);

    const ObjectRenderer& objects() const { return objects_; }
    const FrameUniforms& frame() const { return frame_; }

private:
    const DataSet& data_;
    FrameUniforms frame_;
    SkyPass sky_;
    ObjectRenderer objects_;
    StreamedMesh streamed_;
    std::unique_ptr<TerrainMesh> mesh_;
    std::unique_ptr<BlockTerrain> blocks_;
    glm::dmat4 clip_{1.0};
};

} // namespace overflight::gl
