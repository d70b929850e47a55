#include "sim/FixedStepClock.h"

#include "core/Error.h"

#include <cmath>

namespace overflight {

FixedStepClock::FixedStepClock(double step, int max_steps) : step_(step), max_steps_(max_steps) {
    if (!(step > 0) || !std::isfinite(step)) throw Error("clock", "step must be a positive number of seconds");
    if (max_steps < 1) throw Error("clock", "max_steps must be at least 1");
}

int FixedStepClock::advance(double seconds) {
    if (std::isfinite(seconds) && seconds > 0) accumulator_ += seconds;
    // Counting by floor() rather than repeated subtraction keeps the result
    // exact for whole multiples of the step up to rounding of one division;
    // the tiny tolerance absorbs 0.01 not being representable in binary.
    double due = std::floor(accumulator_ / step_ + 1e-9);
    if (due > max_steps_) {
        // fmod is exact, so even an absurd stall leaves a sane remainder.
        const double rem = std::fmod(accumulator_, step_);
        dropped_ += accumulator_ - rem - max_steps_ * step_;
        accumulator_ = rem + max_steps_ * step_;
        due = max_steps_;
    }
    accumulator_ -= due * step_;
    if (accumulator_ < 0) accumulator_ = 0;
    const int steps = int(due);
    return steps;
}

} // namespace overflight
