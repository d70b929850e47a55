// Based on: Szenberg et al. 1997 sec. 7, Table 1 (wall-clock time of each step).
#include "gl/FinishStepTimer.h"

#include <epoxy/gl.h>

#include <string_view>

namespace overflight::gl {

void FinishStepTimer::begin_frame() {
    glFinish();
    steps_.clear();
    open_ = nullptr;
}

void FinishStepTimer::cpu_step(const char* name, double ms) { steps_.emplace_back(name, ms); }

void FinishStepTimer::begin_gl(const char* name) {
    if (open_) end_gl();
    open_ = name;
    start_ = std::chrono::steady_clock::now();
}

void FinishStepTimer::end_gl() {
    if (!open_) return;
    glFinish();
    cpu_step_since(open_, start_);
    open_ = nullptr;
}

double FinishStepTimer::step(const char* name) const {
    for (const auto& [n, ms] : steps_)
        if (std::string_view(n) == name) return ms;
    return 0;
}

} // namespace overflight::gl
