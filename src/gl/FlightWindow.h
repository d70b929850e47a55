#pragma once
// The interactive `fly` viewer (seed 003 sec. 3.1 and 4): a resizable GLFW
// window in which the hovercraft of sim/Hovercraft.h flies over the terrain,
// seen through sim/ChaseCamera.h, drawn by one of several interchangeable
// terrain methods that share that camera (DESIGN sec. 2).
//
// Keys (seed 003 sec. 3.1, plus Tab, P and H): UP accelerate, DOWN brake,
// LEFT/RIGHT turn (sampled by the 100 Hz physics through KeyState: a tap
// between two steps is still seen by one step, key repeat is ignored), f fog,
// 1 lighting, W wireframe, + / _ level of detail x / ÷ sqrt 2, Tab next
// method (same camera), P screenshot, H HUD, q quit.
//
// Time: the physics runs in fixed 10 ms steps drained from a FixedStepClock.
// Interactive frames feed it wall-clock time; an unattended run (frames > 0)
// feeds it exactly frame_time per frame, so a scripted flight (--press FROM-TO
// in frames) is the same flight on every machine and at any frame rate.
//
// Based on: CMSC 23700 project 2a (seed 003) sec. 3 (vehicle, controls,
// physics, camera) and sec. 4.1-4.2 (sun lighting, GL_EXP fog, sky).
#include "core/Camera.h"
#include "core/DataSet.h"
#include "core/Image.h"
#include "sim/FlightRecord.h"
#include "sim/KeyScript.h"

#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace overflight::gl {

// What the window asks of a method each frame.
struct FlightView {
    const Camera& camera;       // width/height = the framebuffer being drawn
    const Environment& environment; // with the fog / lighting toggles applied
    bool wireframe = false;
};

// A terrain method the window can draw (mesh, voxel, roam, quadtree, ...).
// Methods are created after the GL context exists and draw into the bound
// framebuffer (viewport already set to camera.width x camera.height), sky and
// objects included; they must not allocate per frame in steady state.
class FlightMethod {
public:
    virtual ~FlightMethod() = default;
    virtual const char* name() const = 0;
    // Draws one frame; returns the triangles drawn (0 for methods without any).
    virtual long long draw(const FlightView& view) = 0;
    // Level of detail x factor (seed 003 "+": factor sqrt 2; "_": 1/sqrt 2):
    // a larger triangle budget or a smaller screen error. Methods without a
    // level of detail ignore it.
    virtual void scale_detail(double /*factor*/) {}
    // A short description of the current level of detail for the HUD ("" if none).
    virtual std::string detail() const { return {}; }
};

// Builds the method named `name` for `data` in the current context; returns
// nullptr for a name it does not know. Supplied by the caller (apps/cmd_fly.cpp)
// so that methods from every layer can be offered without gl depending on them.
using FlightMethodFactory = std::function<std::unique_ptr<FlightMethod>(const std::string& name, const DataSet& data)>;

// The method the gl layer itself provides: `mesh`, the full-resolution
// triangulation (TerrainMesh) with sky, sun and fog. Needs a current context.
std::unique_ptr<FlightMethod> make_mesh_flight_method(const DataSet& data);

struct FlightWindowOptions {
    std::vector<std::string> methods{"mesh"}; // Tab cycles through these, in order
    std::string method = "mesh";              // the first one shown
    int width = 1280, height = 720;           // initial window size (resizable)
    double fov = 60.0;
    long long frames = 0;          // > 0: unattended run of exactly this many frames
    double frame_time = 1.0 / 60.0; // simulated seconds per frame in unattended runs
    KeyScript script;              // scripted keys, FROM-TO in frames
    bool hud = true;
    bool visible = true;           // false: hidden window (tests)
    // Start of the vehicle; if !given, the terrain centre facing south.
    VehicleStart start;
};

struct FlightMethodStats {
    std::string method;
    long long frames = 0;
    double seconds = 0;      // wall-clock time spent in those frames
    long long triangles = 0; // sum over the frames
    double fps() const { return seconds > 0 ? frames / seconds : 0; }
};

struct FlightResult {
    FlightRecord record;                  // one entry per frame drawn
    std::vector<FlightMethodStats> per_method; // in order of first use
    long long physics_steps = 0;
};

// Called with the frame's pixels when P is pressed (index 0, 1, 2, ...) and,
// with index -1, after the last frame of an unattended run. The caller writes
// the file (the io layer owns files).
using ScreenshotSink = std::function<void(const ColorImage& image, int index)>;

// Opens the window and runs until q, the window is closed, or `frames` frames
// are done. Throws Error("window", ...) if no window can be opened and
// Error("--method", ...) for a method the factory does not know.
FlightResult run_flight_window(const DataSet& data, const FlightWindowOptions& options,
                               const FlightMethodFactory& factory, const ScreenshotSink& screenshot);

// Renders the cameras of a recorded flight headless (EGL), one image per
// frame, handing each to `sink` with its frame index; `frames` <= 0 means all.
// Camera size width x height, the given fov. Returns per-method stats.
FlightMethodStats render_flight_record(const DataSet& data, const FlightRecord& record, long long frames,
                                       const std::string& method, int width, int height, double fov,
                                       const FlightMethodFactory& factory,
                                       const std::function<void(const ColorImage&, long long frame)>& sink);

} // namespace overflight::gl
