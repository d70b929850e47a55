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
// Every frame (gl/FlightRenderer): the method's terrain for the chase camera,
// then the data set's objects and the hovercraft with the Z-buffer; the HUD
// (gl/Hud) shows fps and the ms of each step of the last timed frame.
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
#include "gl/FlightMethod.h"
#include "sim/FlightRecord.h"
#include "sim/KeyScript.h"

#include <functional>
#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace overflight::gl {

struct FlightWindowOptions {
    std::vector<std::string> methods{"mesh", "voxel", "roam", "quadtree"}; // Tab cycles through these, in order
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
    long long triangles = 0; // terrain triangles, sum over the frames
    long long object_triangles = 0;
    // Step times (FlightStepTimer), summed over the `timed_frames` frames
    // whose timings arrived, in order of first appearance.
    std::vector<std::pair<std::string, double>> step_ms;
    long long timed_frames = 0;
    double fps() const { return seconds > 0 ? frames / seconds : 0; }
    // "raycast:12.31;upload:0.84;..." (mean ms per frame of each step).
    std::string steps_text() const;
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
// are done. Methods come from `factory` (an empty one: make_flight_method of
// FlightMethods.h). Throws Error("window", ...) if no window can be opened and
// Error("--method", ...) for a first method the factory does not know.
FlightResult run_flight_window(const DataSet& data, const FlightWindowOptions& options,
                               const FlightMethodFactory& factory, const ScreenshotSink& screenshot);

// Renders the cameras of a recorded flight headless (EGL), one image per
// frame, handing each to `sink` with its frame index; `frames` <= 0 means all.
// Camera size width x height, the given fov; the objects and the hovercraft at
// its recorded position are drawn as in the window. Returns the method's stats.
FlightMethodStats render_flight_record(const DataSet& data, const FlightRecord& record, long long frames,
                                       const std::string& method, int width, int height, double fov,
                                       const FlightMethodFactory& factory,
                                       const std::function<void(const ColorImage&, long long frame)>& sink);

} // namespace overflight::gl
