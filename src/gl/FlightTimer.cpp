// Based on: Szenberg et al. 1997 sec. 7, Table 1 (time per step of a frame).
#include "gl/FlightTimer.h"

#include <utility>

namespace overflight::gl {

FlightStepTimer::FlightStepTimer(Sink sink) : sink_(std::move(sink)) {
    for (Slot& s : slots_) glCreateQueries(GL_TIME_ELAPSED, FlightSteps::kMax, s.query.data());
}

FlightStepTimer::~FlightStepTimer() {
    if (open_) glEndQuery(GL_TIME_ELAPSED);
    for (Slot& s : slots_) glDeleteQueries(FlightSteps::kMax, s.query.data());
}

bool FlightStepTimer::ready(const Slot& s) const {
    // Queries complete in order: the last GL step of the frame decides.
    for (int i = s.steps.count - 1; i >= 0; --i) {
        if (!s.steps.step[std::size_t(i)].gl) continue;
        GLuint available = 0;
        glGetQueryObjectuiv(s.query[std::size_t(i)], GL_QUERY_RESULT_AVAILABLE, &available);
        return available != 0;
    }
    return true;
}

void FlightStepTimer::deliver(Slot& s) {
    for (int i = 0; i < s.steps.count; ++i) {
        FlightStep& step = s.steps.step[std::size_t(i)];
        if (!step.gl) continue;
        GLuint64 ns = 0;
        glGetQueryObjectui64v(s.query[std::size_t(i)], GL_QUERY_RESULT, &ns);
        step.ms = double(ns) * 1e-6;
    }
    if (sink_) sink_(s.tag, s.steps);
    ++delivered_;
}

void FlightStepTimer::begin_frame(int tag) {
    if (open_) end_gl();
    while (delivered_ < started_ && (started_ - delivered_ >= std::uint64_t(kSlots) || ready(slot(delivered_))))
        deliver(slot(delivered_));
    Slot& s = slot(started_++);
    s.tag = tag;
    s.steps.count = 0;
}

void FlightStepTimer::cpu_step(const char* name, double ms) {
    if (started_ == delivered_) return; // no frame begun
    FlightSteps& f = slot(started_ - 1).steps;
    if (f.count < FlightSteps::kMax) f.step[std::size_t(f.count++)] = FlightStep{name, ms, false};
}

void FlightStepTimer::begin_gl(const char* name) {
    if (started_ == delivered_ || open_) return;
    Slot& s = slot(started_ - 1);
    if (s.steps.count >= FlightSteps::kMax) return;
    glBeginQuery(GL_TIME_ELAPSED, s.query[std::size_t(s.steps.count)]);
    s.steps.step[std::size_t(s.steps.count++)] = FlightStep{name, 0.0, true};
    open_ = true;
}

void FlightStepTimer::end_gl() {
    if (!open_) return;
    glEndQuery(GL_TIME_ELAPSED);
    open_ = false;
}

void FlightStepTimer::flush() {
    if (open_) end_gl();
    while (delivered_ < started_) deliver(slot(delivered_));
}

} // namespace overflight::gl
