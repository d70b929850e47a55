#pragma once
// The interactive `fly` viewer: a resizable GLFW window in which the
// FlightSession (sim/FlightSession.h: hovercraft, keys, chase camera, record)
// is drawn every frame by a terrain method of the method table
// (methods/MethodTable.h) through the Compositor, with the HUD on top. The
// window only turns GLFW events into keys and draws; the flight itself runs
// without it in tests.
//
// An image method (the ray casters) runs one frame ahead of the screen: the
// cast of frame N+1 and the copy of its images into the compositor's
// persistently mapped pixel buffers (Compositor::stage) run on a oneTBB task
// while the GL thread loads, composites and shows frame N, each frame drawn
// with the camera, vehicle and toggles it was cast for. The physics keeps its
// fixed steps (the session is advanced once per frame, as before); what
// changes is that a key shows on screen one frame later. Mesh methods, whose
// arrays the compositor reads while drawing, run in step with the screen.
//
// Keys (CMSC 23700 hovercraft project sec. 3.1, plus Tab, P and H): UP
// accelerate, DOWN brake, LEFT/RIGHT turn, f fog (off, GL_EXP, atmosphere), 1 lighting, W wireframe,
// + / _ level of detail x / ÷ sqrt 2, Tab next method (same camera), P
// screenshot (with the frame's camera file), H HUD, q quit.
//
// Based on: CMSC 23700 project 2a, "sports utility hovercraft", sec. 3 and
// 4.1-4.2; Szenberg et al. 1997 sec. 5 (any terrain composited with the same
// Z-buffered objects).
#include "core/Camera.h"
#include "core/DataSet.h"
#include "core/Image.h"
#include "methods/MethodTable.h"
#include "sim/FlightRecord.h"
#include "sim/FlightSession.h"

#include <functional>
#include <string>
#include <utility>
#include <vector>

namespace overflight::gl {

struct FlightWindowOptions {
    std::string method = "mesh";    // the first one shown (any row of the table); Tab cycles the fly rows
    int width = 1280, height = 720; // initial window size (resizable)
    FlightSessionOptions session;
    bool visible = true;            // false: hidden window (tests)
};

struct FlightMethodStats {
    std::string method;
    long long frames = 0;
    double seconds = 0;      // wall-clock time spent in those frames
    long long triangles = 0; // terrain triangles, sum over the frames
    long long object_triangles = 0;
    // Step times, summed over the `timed_frames` frames whose timings
    // arrived, in order of first appearance.
    std::vector<std::pair<std::string, double>> step_ms;
    long long timed_frames = 0;
    double fps() const { return seconds > 0 ? frames / seconds : 0; }
    // Adds one frame's step times.
    void add_steps(const std::vector<std::pair<const char*, double>>& steps);
    // "raycast:12.31;color_upload:0.84;..." (mean ms per frame of each step).
    std::string steps_text() const;
};

struct FlightResult {
    FlightRecord record;                       // one entry per frame drawn
    std::vector<FlightMethodStats> per_method; // in order of first use
    long long physics_steps = 0;
};

// Called with the frame's pixels and camera when P is pressed (index 0, 1, 2, ...) and,
// with index -1, after the last frame of an unattended run. The caller writes
// the file (the io layer owns files).
using ScreenshotSink = std::function<void(const ColorImage& image, const Camera& camera, int index)>;

// Opens the window and runs until q, the window is closed, or the session's
// frames are done. Methods are built from the table with `methods`. Throws
// Error("window", ...) if no window can be opened, Error("terrain method", ...) for a
// first method not in the table, and what the session and methods throw.
FlightResult run_flight_window(const DataSet& data, const FlightWindowOptions& options, const MethodContext& methods,
                               const ScreenshotSink& screenshot);

// Renders the cameras of a recorded flight headless (EGL), one image per
// frame, handing each to `sink` with its frame index; `frames` <= 0 means all.
// Camera size width x height, the given fov; the objects and the hovercraft at
// its recorded position are drawn as in the window. Returns the method's stats.
FlightMethodStats render_flight_record(const DataSet& data, const FlightRecord& record, long long frames,
                                       const MethodEntry& method, const MethodContext& methods, int width, int height,
                                       double fov, const std::function<void(const ColorImage&, long long frame)>& sink);

} // namespace overflight::gl
