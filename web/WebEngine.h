#pragma once
// The engine of the web page, as the page's JavaScript calls it: the core's
// flight (sim/FlightSession.h: the hovercraft at 100 Hz, the chase camera,
// the viewer's keys) and the frame of one of two terrain methods, the same
// code `fly` runs, built for WebAssembly (web/CMakeLists.txt):
//   - `voxel` (raycast/VoxelRenderer.h: sun light, Floating Horizon cast,
//     water): the page uploads the color and depth images and draws the
//     objects over them with the Z-buffer and of_view_proj;
//   - `roam` (lod/RoamMesh.h: split-only ROAM within a triangle budget, the
//     vehicle's triangles first): the page uploads the mesh's plain arrays
//     into WebGL2 buffers and draws them, as the native renderer draws any
//     method's mesh.
//
// One engine per module instance, one thread. Functions returning int return
// 0 on success and a negative code on failure, of_error() then saying why in
// one line. Pointers returned stay valid until the next call of any function
// (memory growth may move the heap: take views of HEAPU8 afresh after each).
#include <cstdint>

#ifdef __EMSCRIPTEN__
#include <emscripten/emscripten.h>
#define OF_EXPORT EMSCRIPTEN_KEEPALIVE
#else
#define OF_EXPORT
#endif

extern "C" {

// Failure codes.
enum {
    OF_BAD_FILE = -1,     // the bytes are not a valid OFTERR01 file (core/WebTerrainFormat.h)
    OF_NO_TERRAIN = -2,   // nothing loaded yet
    OF_BAD_ARGUMENT = -3, // a size, camera or start the engine cannot use
    OF_FAILED = -4,       // anything else (out of memory)
};

// Decodes an OFTERR01 file (`size` bytes at `bytes`, which the caller owns
// and may free afterwards) and starts a flight on it: the vehicle at the
// file's start (else the terrain's centre, facing south), sun lighting unless
// the file bakes it, the chase camera (60 degree field of view, as `fly`).
// Replaces any terrain loaded before; on failure keeps it.
OF_EXPORT int of_load_terrain(const std::uint8_t* bytes, int size);

// The image size of the next frames, 1..16384 pixels each way (default 1280x720).
OF_EXPORT int of_set_size(int width, int height);

// A key going down (down != 0) or up: `key` is sim/KeyState.h's Key value
// (0 accelerate, 1 brake, 2 left, 3 right, 4 fog, 5 lighting, ..., 13 shadows,
// 14 sun later, 15 sun earlier, 16 water). Unknown values are ignored.
// Vehicle keys are sampled by the physics; the others toggle at the next frame.
OF_EXPORT void of_key(int key, int down);

// One frame: the toggles of keys pressed since the last, `wall_seconds` of
// physics (the real time since the last frame; at most 0.25 s counts), the
// chase camera, then the current method's output for the frame's camera
// (the pinned one if of_set_camera was called): the voxel method's color and
// depth, or the ROAM mesh (rebuilt only when the camera, the vehicle or the
// budget changed). The detail keys (7 up, 8 down) step the ROAM budget by
// sqrt 2 as `fly`'s + and _ do (lod/RoamMesh.h roam_scale_budget).
OF_EXPORT int of_frame(double wall_seconds);

// The terrain method of the next frames: 0 voxel (default), 1 roam. The
// outputs of the other method keep their last frame's contents.
enum { OF_METHOD_VOXEL = 0, OF_METHOD_ROAM = 1 };
OF_EXPORT int of_set_method(int method);
// ROAM's triangle budget per frame, 2..2^24 (default OF_ROAM_DEFAULT_BUDGET:
// the page's software WebGL2 draws it at frame rate; `fly` starts at 65536).
enum { OF_ROAM_DEFAULT_BUDGET = 32768 };
OF_EXPORT int of_set_roam_budget(int triangles);
OF_EXPORT int of_roam_budget();

// The last ROAM mesh as plain arrays (core/MeshArrays.h): per vertex a world
// position (3 floats), a unit normal (3 floats) and the terrain's color
// (RGB8, 3 bytes); a triangle list of 32-bit vertex indices, counter-clockwise
// seen from above. Empty before the first ROAM frame.
OF_EXPORT const float* of_mesh_positions();
OF_EXPORT const float* of_mesh_normals();
OF_EXPORT const std::uint8_t* of_mesh_colors();
OF_EXPORT const std::uint32_t* of_mesh_indices();
OF_EXPORT int of_mesh_vertex_count();
OF_EXPORT int of_mesh_index_count();
// Incremented each time the arrays are rebuilt (the page uploads only then).
OF_EXPORT double of_mesh_version();
// The last ROAM frame's lod/RoamMesh.h statistics: {triangles, vertices,
// splits, forced splits, deepest level, largest and mean projected error in
// pixels, milliseconds to tessellate and write the arrays}.
OF_EXPORT const double* of_roam_stats();

// The sun of the last frame's environment (the time-of-day keys move it
// along core/SunLight.h's day arc): {azimuth (degrees clockwise from north),
// elevation (degrees), then the unit direction towards the sun x, y, z}.
OF_EXPORT const double* of_sun();

// The last frame's color, RGB8, width*height pixels, row 0 at the TOP (as the
// native method's images and PNG files; OpenGL's row 0 is the bottom).
OF_EXPORT std::uint8_t* of_color();
// The last frame's OpenGL window depth in [0,1] (1 = sky) for the camera's
// near and far, width*height floats, row 0 at the top.
OF_EXPORT float* of_depth();
OF_EXPORT int of_width();
OF_EXPORT int of_height();

// What the last frame cost, in milliseconds: {the whole of_frame, the
// physics and camera (sim/FlightSession.h), the voxel method's lighting (0
// unless relit), its per-frame tables, cast, resolve (raycast/RaycastOptions.h
// RaycastStats: cast and resolve are fused per block, their wall time split
// by thread time) and water pass, the ROAM tessellation}.
OF_EXPORT const double* of_frame_stats();

// The last frame's projection * view (16 floats, column-major, world
// coordinates in, clip coordinates out): what the native object pass uses.
OF_EXPORT const float* of_view_proj();
// The last frame's camera: {eye x, y, z, heading, pitch, fov, near, far}.
OF_EXPORT const double* of_camera();
// The vehicle after the last frame: {x, y, z, heading (degrees), velocity}.
OF_EXPORT const double* of_vehicle();
// Where the last frame's hovercraft body sits, as `fly` draws it
// (sim/VehicleBody.h vehicle_frame): {origin x, y, z, right x, y, z, up x, y,
// z, forward x, y, z}; the body's model (the site's vehicle.bin) is in the
// frame whose origin is its base's centre, +Z forward.
OF_EXPORT const double* of_vehicle_frame();
// The scene objects' world boxes (`count` boxes of 6 floats: lo x, y, z, hi
// x, y, z; the site's objects.bin holds them), copied: the frames after this
// call bound the objects' pixels with them (of_depth_rect).
OF_EXPORT int of_set_object_bounds(const float* boxes, int count);
// The last frame's pixels that objects can cover: the union of the screen
// rectangles of the objects' boxes and, with the chase camera, the
// vehicle's body (core/ScreenRect.h screen_rect): {col0, row0, col1, row1},
// columns [col0, col1) and rows [row0, row1) from the top; empty (col1 <=
// col0) when none is in view. Outside it no object fragment is drawn, so the
// page needs the ray caster's depth only inside it (the native compositor's
// depth load, Szenberg et al. 1997 Table 1 "Z-buffer load").
OF_EXPORT const int* of_depth_rect();
// Physics steps (10 ms each) run since the terrain was loaded.
OF_EXPORT double of_physics_steps();
// The viewer's toggles: bit 0 HUD, 1 sun lighting, 2 shadows, 3 water, bits
// 4-5 the fog mode (0 off, 1 GL_EXP, 2 atmosphere), bit 6 the hovercraft
// drawn (the chase camera; a pinned camera is `render`'s, which draws none).
OF_EXPORT int of_toggles();

// Pins the camera of the next frames (the vehicle keeps flying): eye in world
// coordinates, heading and pitch and horizontal fov in degrees, near and far
// along the view axis; a near or far that is not a positive number takes
// `render`'s default (1, and the terrain's diagonal x 1.05). Shear projection.
OF_EXPORT int of_set_camera(double x, double y, double z, double heading, double pitch, double fov, double near,
                            double far);
// Back to the chase camera.
OF_EXPORT void of_follow_vehicle();

// The last failure's one-line message ("" if none).
OF_EXPORT const char* of_error();

} // extern "C"
