#pragma once
// Based on: CMSC 23700 project 2a sec. 3.2: "We recompute the state
// of the vehicle one hundred times per second", whatever the frame rate. The
// fixed-step time accumulator ("Fix your timestep", G. Fiedler 2004): frame
// time is added to an accumulator and drained in whole physics steps, so the
// simulation is the same at 20 fps and at 500 fps.

namespace overflight {

class FixedStepClock {
public:
    // step: seconds per physics step (0.01 for the hovercraft). max_steps: the
    // most steps one advance() may ask for; time beyond that is dropped, so a
    // stalled frame (window dragged, debugger) slows the simulation down instead
    // of making every later frame slower still (the "spiral of death").
    explicit FixedStepClock(double step = 0.01, int max_steps = 25);

    // Adds `seconds` of real time (negative or non-finite counts as 0) and
    // returns how many whole steps are now due; the remainder carries over.
    int advance(double seconds);

    // Fraction of a step left in the accumulator, in [0, 1): for interpolating
    // the drawn state between the last two physics states.
    double alpha() const { return accumulator_ / step_; }
    double step() const { return step_; }
    // Seconds dropped because a frame asked for more than max_steps.
    double dropped() const { return dropped_; }
    void reset() { accumulator_ = 0; dropped_ = 0; }

private:
    double step_;
    int max_steps_;
    double accumulator_ = 0;
    double dropped_ = 0;
};

} // namespace overflight
