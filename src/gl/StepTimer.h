#pragma once
// Where the compositor reports the time of each step of a frame (the steps of
// Szenberg et al. 1997 Table 1: ray cast, color buffer load, Z-buffer load,
// objects). Two clocks implement it: FinishStepTimer for headless frames
// (`render`, `bench`, replays: every GL step ends in glFinish, so a step's
// time includes the GL work it queued, as the paper's wall-clock timings do)
// and FlightStepTimer for the window (GL timer queries read frames later, so
// timing never stalls the pipeline it measures).
#include <chrono>

namespace overflight::gl {

class StepTimer {
public:
    virtual ~StepTimer() = default;
    // A step done on the CPU, `ms` milliseconds (name: a string literal).
    virtual void cpu_step(const char* name, double ms) = 0;
    // A GL step: the commands issued between begin_gl and end_gl. Not nested.
    virtual void begin_gl(const char* name) = 0;
    virtual void end_gl() = 0;

    // cpu_step(name, milliseconds from `start` to now).
    void cpu_step_since(const char* name, std::chrono::steady_clock::time_point start) {
        cpu_step(name, std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count());
    }
};

} // namespace overflight::gl
