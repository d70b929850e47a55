#pragma once
// A StepTimer for headless frames: a GL step lasts from begin_gl to the
// glFinish() in end_gl, timed on the CPU's steady clock, so it includes the
// GL work the step queued. Steps are kept in execution order.
#include "gl/StepTimer.h"

#include <string>
#include <utility>
#include <vector>

namespace overflight::gl {

class FinishStepTimer final : public StepTimer {
public:
    // Starts a frame: forgets the previous steps and waits for queued GL work
    // (so that it is not charged to the first step).
    void begin_frame();
    void cpu_step(const char* name, double ms) override;
    void begin_gl(const char* name) override;
    void end_gl() override;

    const std::vector<std::pair<const char*, double>>& steps() const { return steps_; }
    double step(const char* name) const; // 0 when absent

private:
    std::vector<std::pair<const char*, double>> steps_;
    const char* open_ = nullptr;
    std::chrono::steady_clock::time_point start_;
};

} // namespace overflight::gl
