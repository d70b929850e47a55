// The web page's engine. See WebEngine.h.
#include "WebEngine.h"

#include "core/Camera.h"
#include "core/Error.h"
#include "core/Image.h"
#include "core/MeshArrays.h"
#include "core/ScreenRect.h"
#include "core/SunLight.h"
#include "core/WebTerrainFormat.h"
#include "lod/RoamMesh.h"
#include "raycast/RaycastOptions.h"
#include "raycast/VoxelRenderer.h"
#include "sim/FlightSession.h"
#include "sim/KeyState.h"
#include "sim/VehicleBody.h"

#include <glm/mat4x4.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <exception>
#include <memory>
#include <new>
#include <optional>
#include <span>
#include <string>
#include <vector>

using namespace overflight;

namespace {

// `fly`'s default field of view.
constexpr double kFov = 60.0;

// A loaded terrain and its flight. The session and the renderer keep
// references to the terrain: it lives as long as they do.
struct Flight {
    explicit Flight(WebTerrain decoded) : data(std::move(decoded)) {
        // As `fly`: baked lighting in the file is where the lighting key starts.
        FlightSessionOptions options;
        options.fov = kFov;
        options.start = data.start;
        options.lighting = !lighting_is_baked(data.environment);
        options.record = false;
        data.environment.baked = false;
        session = std::make_unique<FlightSession>(data.terrain, data.environment, options);
        renderer = std::make_unique<VoxelRenderer>(data.terrain, RaycastOptions{});
    }
    WebTerrain data;
    std::unique_ptr<FlightSession> session;
    std::unique_ptr<VoxelRenderer> renderer;
    std::unique_ptr<RoamMesh> roam; // its variance tree built on the first ROAM frame
};

// The arrays go to the page as they are: 3 floats per vec3, 3 bytes per color.
static_assert(sizeof(glm::vec3) == 3 * sizeof(float) && sizeof(Rgb8) == 3);

// What a ROAM mesh was built for: the same again needs no rebuild.
struct RoamKey {
    glm::dvec3 eye{0.0};
    double heading = 0, pitch = 0, fov = 0, near = 0, far = 0;
    int width = 0, height = 0, budget = 0;
    std::optional<glm::dvec2> focus;
    friend bool operator==(const RoamKey&, const RoamKey&) = default;
};

struct Engine {
    std::unique_ptr<Flight> flight;
    int width = 1280, height = 720;
    std::optional<Camera> pinned;
    int method = OF_METHOD_VOXEL;
    int roam_budget = OF_ROAM_DEFAULT_BUDGET;
    ColorImage color;
    DepthImage depth;
    MeshArrays mesh;
    std::optional<RoamKey> mesh_for; // empty: no mesh yet, or a new terrain
    double mesh_version = 0;
    double roam_stats[8] = {};
    double frame_stats[8] = {};
    double sun[5] = {};
    float view_proj[16] = {};
    double camera[8] = {};
    double vehicle[5] = {};
    double vehicle_frame[12] = {};
    std::vector<WorldBox> object_bounds;
    std::vector<WorldBox> frame_bounds; // the objects' and, if drawn, the vehicle's: reused every frame
    int depth_rect[4] = {};
    std::string error;
};

Engine& engine() {
    static Engine e;
    return e;
}

double ms_since(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

// Runs `f`, turning an exception into `code` (Error) or OF_FAILED (anything
// else) and the message of_error() returns.
template <typename F>
int guarded(int code, const F& f) {
    Engine& e = engine();
    try {
        f(e);
        e.error.clear();
        return 0;
    } catch (const Error& x) {
        e.error = x.what();
        return code;
    } catch (const std::bad_alloc&) {
        e.error = "out of memory";
        return OF_FAILED;
    } catch (const std::exception& x) {
        e.error = x.what();
        return OF_FAILED;
    }
}

// The ROAM method's frame (methods/RoamMethod.cpp): tessellate for the
// camera within the budget, the vehicle's triangles first unless the camera
// is pinned (as `render`, which has no vehicle), then the plain arrays.
void roam_frame(Engine& e, const Camera& cam) {
    Flight& f = *e.flight;
    std::optional<glm::dvec2> focus;
    if (!e.pinned) focus = glm::dvec2(f.session->vehicle().x, f.session->vehicle().z);
    const RoamKey key{cam.eye, cam.heading, cam.pitch, cam.fov, cam.near, cam.far,
                      cam.width, cam.height, e.roam_budget, focus};
    if (e.mesh_for == key) return;
    if (!f.roam) f.roam = std::make_unique<RoamMesh>(f.data.terrain);
    const auto t0 = std::chrono::steady_clock::now();
    const RoamStats s = f.roam->tessellate(cam, e.roam_budget, focus);
    f.roam->write_mesh(e.mesh);
    const double ms = ms_since(t0);
    const double stats[8] = {double(e.mesh.triangle_count()), double(e.mesh.positions.size()), double(s.splits),
                             double(s.forced_splits), double(s.max_level), s.max_error_px, s.mean_error_px, ms};
    std::copy(stats, stats + 8, e.roam_stats);
    e.mesh_for = key;
    ++e.mesh_version;
}

} // namespace

extern "C" {

int of_load_terrain(const std::uint8_t* bytes, int size) {
    return guarded(OF_BAD_FILE, [&](Engine& e) {
        if (!bytes || size < 0) throw Error("terrain file", "no bytes given");
        auto flight = std::make_unique<Flight>(
            decode_web_terrain(std::span<const std::uint8_t>(bytes, std::size_t(size)), "terrain file"));
        e.flight = std::move(flight);
        e.pinned.reset();
        e.mesh.clear();
        e.mesh_for.reset();
        ++e.mesh_version;
    });
}

int of_set_size(int width, int height) {
    return guarded(OF_BAD_ARGUMENT, [&](Engine& e) {
        if (width < 1 || height < 1 || width > 16384 || height > 16384)
            throw Error("size", std::to_string(width) + "x" + std::to_string(height) +
                                    " is outside 1..16384 pixels each way");
        e.width = width;
        e.height = height;
    });
}

void of_key(int key, int down) {
    Engine& e = engine();
    if (!e.flight || key < 0 || key >= kKeyCount) return;
    if (down) e.flight->session->press(Key(key));
    else e.flight->session->release(Key(key));
}

int of_frame(double wall_seconds) {
    Engine& e = engine();
    if (!e.flight) {
        e.error = "no terrain loaded";
        return OF_NO_TERRAIN;
    }
    return guarded(OF_FAILED, [&](Engine& en) {
        const auto t0 = std::chrono::steady_clock::now();
        double* fs = en.frame_stats;
        std::fill(fs, fs + 8, 0.0);
        FlightSession& s = *en.flight->session;
        // The detail keys step the ROAM budget as `fly` does; the other
        // commands (method, screenshot, quit) are the page's.
        for (Key k : s.begin_frame()) {
            if (k == Key::DetailUp) en.roam_budget = roam_scale_budget(en.roam_budget, 1);
            if (k == Key::DetailDown) en.roam_budget = roam_scale_budget(en.roam_budget, -1);
        }
        s.advance(wall_seconds);
        Camera cam = en.pinned ? *en.pinned : s.camera();
        cam.width = en.width;
        cam.height = en.height;
        const Environment env = s.environment();
        fs[1] = ms_since(t0);
        if (en.method == OF_METHOD_ROAM) {
            const double built = en.mesh_version;
            roam_frame(en, cam);
            if (en.mesh_version != built) fs[7] = en.roam_stats[7];
        } else {
            VoxelFrameStats stats;
            en.flight->renderer->render(cam, env, en.color, en.depth, stats);
            fs[2] = stats.light_ms;
            fs[3] = stats.raycast.ms_setup;
            fs[4] = stats.raycast.ms_cast;
            fs[5] = stats.raycast.ms_resolve;
            fs[6] = stats.water_ms;
        }
        const SunAngles sun = sun_angles(env.sun_dir);
        const glm::dvec3 to_sun = glm::normalize(glm::dvec3(env.sun_dir));
        const double sun_out[5] = {sun.azimuth, sun.elevation, to_sun.x, to_sun.y, to_sun.z};
        std::copy(sun_out, sun_out + 5, en.sun);
        const glm::mat4 vp(cam.projection_matrix() * cam.view_matrix());
        for (int c = 0; c < 4; ++c)
            for (int r = 0; r < 4; ++r) en.view_proj[4 * c + r] = vp[c][r];
        const double camera[8] = {cam.eye.x, cam.eye.y, cam.eye.z, cam.heading, cam.pitch, cam.fov, cam.near, cam.far};
        std::copy(camera, camera + 8, en.camera);
        const HovercraftState& v = s.vehicle();
        const double vehicle[5] = {v.x, v.y, v.z, v.heading, v.velocity};
        std::copy(vehicle, vehicle + 5, en.vehicle);
        const BodyFrame body = vehicle_frame(en.flight->data.terrain, v.x, v.z, v.heading);
        const glm::dvec3 axes[4] = {body.origin, body.ax, body.ay, body.az};
        for (int k = 0; k < 4; ++k)
            for (int c = 0; c < 3; ++c) en.vehicle_frame[3 * k + c] = axes[k][c];
        // Half a metre around the body covers the float rounding of its
        // placed vertices, as natively (gl/FlightVehicle.h bounds_at).
        en.frame_bounds.assign(en.object_bounds.begin(), en.object_bounds.end());
        if (!en.pinned) en.frame_bounds.push_back(placed_box(body, vehicle_local_box(), 0.5));
        const PixelRect r = screen_rect(en.frame_bounds, cam);
        const int rect[4] = {r.col0, r.row0, r.col1, r.row1};
        std::copy(rect, rect + 4, en.depth_rect);
        s.end_frame();
        fs[0] = ms_since(t0);
    });
}

int of_set_method(int method) {
    return guarded(OF_BAD_ARGUMENT, [&](Engine& e) {
        if (method != OF_METHOD_VOXEL && method != OF_METHOD_ROAM)
            throw Error("method", std::to_string(method) + " is neither 0 (voxel) nor 1 (roam)");
        e.method = method;
    });
}

int of_set_roam_budget(int triangles) {
    return guarded(OF_BAD_ARGUMENT, [&](Engine& e) {
        if (triangles < 2 || triangles > (1 << 24))
            throw Error("triangle budget", std::to_string(triangles) + " is outside 2..16777216");
        e.roam_budget = triangles;
    });
}

int of_roam_budget() { return engine().roam_budget; }

const float* of_mesh_positions() { return reinterpret_cast<const float*>(engine().mesh.positions.data()); }
const float* of_mesh_normals() { return reinterpret_cast<const float*>(engine().mesh.normals.data()); }
const std::uint8_t* of_mesh_colors() { return reinterpret_cast<const std::uint8_t*>(engine().mesh.colors.data()); }
const std::uint32_t* of_mesh_indices() { return engine().mesh.indices.data(); }
int of_mesh_vertex_count() { return int(engine().mesh.positions.size()); }
int of_mesh_index_count() { return int(engine().mesh.indices.size()); }
double of_mesh_version() { return engine().mesh_version; }
const double* of_roam_stats() { return engine().roam_stats; }
const double* of_sun() { return engine().sun; }
const double* of_frame_stats() { return engine().frame_stats; }

std::uint8_t* of_color() { return reinterpret_cast<std::uint8_t*>(engine().color.pixels.data()); }
float* of_depth() { return engine().depth.pixels.data(); }
int of_width() { return engine().color.width; }
int of_height() { return engine().color.height; }
const float* of_view_proj() { return engine().view_proj; }
const double* of_camera() { return engine().camera; }
const double* of_vehicle() { return engine().vehicle; }
const double* of_vehicle_frame() { return engine().vehicle_frame; }
const int* of_depth_rect() { return engine().depth_rect; }

int of_set_object_bounds(const float* boxes, int count) {
    return guarded(OF_BAD_ARGUMENT, [&](Engine& e) {
        if (count < 0 || (count > 0 && !boxes)) throw Error("object bounds", "no boxes given");
        std::vector<WorldBox> bounds(static_cast<std::size_t>(count));
        for (int k = 0; k < count; ++k) {
            const float* b = boxes + 6 * k;
            bounds[std::size_t(k)] = {glm::vec3(b[0], b[1], b[2]), glm::vec3(b[3], b[4], b[5])};
        }
        e.object_bounds = std::move(bounds);
    });
}

double of_physics_steps() {
    const Engine& e = engine();
    return e.flight ? double(e.flight->session->physics_steps()) : 0.0;
}

int of_toggles() {
    const Engine& e = engine();
    if (!e.flight) return 0;
    const ViewToggles& t = e.flight->session->toggles();
    return (t.hud ? 1 : 0) | (t.lighting ? 2 : 0) | (t.shadows ? 4 : 0) | (t.water ? 8 : 0) | (int(t.fog) << 4) |
           (e.pinned ? 0 : 64);
}

int of_set_camera(double x, double y, double z, double heading, double pitch, double fov, double near, double far) {
    Engine& e = engine();
    if (!e.flight) {
        e.error = "no terrain loaded";
        return OF_NO_TERRAIN;
    }
    return guarded(OF_BAD_ARGUMENT, [&](Engine& en) {
        const Terrain& t = en.flight->data.terrain;
        Camera cam;
        cam.eye = {x, y, z};
        cam.heading = heading;
        cam.pitch = pitch;
        cam.fov = fov;
        cam.width = en.width;
        cam.height = en.height;
        // `render`'s defaults (apps/CameraOptions.cpp).
        cam.near = near > 0 ? near : 1.0;
        cam.far = far > 0 ? far : std::hypot(t.width(), t.depth()) * 1.05;
        cam.projection = Projection::Shear;
        cam.validate();
        en.pinned = cam;
    });
}

void of_follow_vehicle() { engine().pinned.reset(); }

const char* of_error() { return engine().error.c_str(); }

} // extern "C"
