#pragma once
// Per-frame step timings of the `fly` window (the HUD shows ms per step: ray cast or
// tessellate, uploads, objects), the interactive analogue
// of Szenberg et al. 1997 Table 1 (time of each step of the composite).
//
// CPU steps (ray cast, tessellation, buffer fills) are timed by the caller on
// the steady clock. GL steps are bracketed by GL_TIME_ELAPSED queries whose
// results are read a few frames later, so timing never stalls the pipeline
// (no glFinish per step, which would lower the frame rate it measures). On a
// GPU a GL step is the GPU time of its commands. Mesa's llvmpipe rasterises a
// draw only when its bins are flushed (at the swap, or when they fill up), so
// there the GL steps of small draws read far below their cost; the frame time
// is the reliable total on such a renderer.
#include "gl/StepTimer.h"

#include <epoxy/gl.h>

#include <array>
#include <chrono>
#include <cstdint>
#include <functional>

namespace overflight::gl {

struct FlightStep {
    const char* name = ""; // a string literal ("ray cast", "upload", ...)
    double ms = 0;
    bool gl = false;       // timed by a GL query (GPU time) rather than on the CPU
};

struct FlightSteps {
    static constexpr int kMax = 12;
    std::array<FlightStep, kMax> step{};
    int count = 0;
};

class FlightStepTimer final : public StepTimer {
public:
    // Receives each frame's steps, in frame order, once all of its GL results
    // are in, with the tag given to begin_frame (the window passes the method).
    using Sink = std::function<void(int tag, const FlightSteps& steps)>;

    // Creates the queries in the current GL context.
    explicit FlightStepTimer(Sink sink);
    ~FlightStepTimer();
    FlightStepTimer(const FlightStepTimer&) = delete;
    FlightStepTimer& operator=(const FlightStepTimer&) = delete;

    // Starts a frame (delivering the finished ones first). Steps beyond
    // FlightSteps::kMax in one frame are dropped.
    void begin_frame(int tag);
    void cpu_step(const char* name, double ms) override;
    void begin_gl(const char* name) override;
    void end_gl() override;
    // Waits for the results of every frame still pending and delivers them.
    void flush();

private:
    static constexpr int kSlots = 4; // frames in flight before a result is waited for
    struct Slot {
        int tag = 0;
        FlightSteps steps;
        std::array<GLuint, FlightSteps::kMax> query{};
    };
    Slot& slot(std::uint64_t frame) { return slots_[frame % kSlots]; }
    bool ready(const Slot& s) const;
    void deliver(Slot& s);

    Sink sink_;
    std::array<Slot, kSlots> slots_;
    std::uint64_t started_ = 0;   // frames begun
    std::uint64_t delivered_ = 0; // frames handed to the sink
    bool open_ = false;           // inside begin_gl / end_gl
};

} // namespace overflight::gl
