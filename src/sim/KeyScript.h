#pragma once
// Scripted key presses for unattended runs (DESIGN sec. 6): `--press
// KEY:FROM-TO` holds KEY during steps (sim) or frames (fly) FROM to TO-1, the
// end excluded. The vehicle keys are held, as if a person held the arrow key;
// the viewer's command keys (fog, next-method, screenshot, ...) fire once, on
// the FROM frame, as a key press does. Key names are those of key_name().
#include "sim/KeyState.h"

#include <string_view>
#include <utility>
#include <vector>

namespace overflight {

struct ScriptedPress {
    Key key = Key::Accelerate;
    long long from = 0; // first step/frame held
    long long to = 0;   // first step/frame no longer held (> from)
};

// Parses "KEY:FROM-TO" (e.g. "accelerate:0-100"). Throws Error("key press", ...)
// for an unknown key, a missing or negative bound, or TO <= FROM.
ScriptedPress parse_press(std::string_view spec);

class KeyScript {
public:
    KeyScript() = default;
    explicit KeyScript(std::vector<ScriptedPress> presses) : presses_(std::move(presses)) {}

    // Vehicle keys held at step/frame t.
    Controls controls_at(long long t) const;
    // True if `key` is held at t.
    bool held_at(Key key, long long t) const;
    // True if a press of `key` starts at t (the one-shot event of a command key).
    bool starts_at(Key key, long long t) const;

    const std::vector<ScriptedPress>& presses() const { return presses_; }
    bool empty() const { return presses_.empty(); }

private:
    std::vector<ScriptedPress> presses_;
};

} // namespace overflight
