#include "sim/KeyScript.h"

#include "core/Error.h"

#include <charconv>
#include <string>

namespace overflight {

namespace {
bool parse_count(std::string_view text, long long& out) {
    if (text.empty()) return false;
    const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), out);
    return ec == std::errc() && end == text.data() + text.size() && out >= 0;
}
} // namespace

ScriptedPress parse_press(std::string_view spec) {
    const std::string quoted = "'" + std::string(spec) + "'";
    const auto colon = spec.find(':');
    if (colon == std::string_view::npos)
        throw Error("key press", quoted + " is not KEY:FROM-TO (e.g. accelerate:0-100)");
    const std::string_view name = spec.substr(0, colon);
    const auto key = key_from_name(name);
    if (!key) {
        std::string names;
        for (int i = 0; i < kKeyCount; ++i) names += std::string(i ? ", " : "") + key_name(Key(i));
        throw Error("key press", "unknown key '" + std::string(name) + "' (keys: " + names + ")");
    }
    const std::string_view range = spec.substr(colon + 1);
    const auto dash = range.find('-');
    ScriptedPress p;
    p.key = *key;
    if (dash == std::string_view::npos || !parse_count(range.substr(0, dash), p.from) ||
        !parse_count(range.substr(dash + 1), p.to))
        throw Error("key press", quoted + ": FROM-TO must be two non-negative whole numbers, e.g. 0-100");
    if (p.to <= p.from) throw Error("key press", quoted + ": TO must be greater than FROM (the end is excluded)");
    return p;
}

bool KeyScript::held_at(Key key, long long t) const {
    for (const ScriptedPress& p : presses_)
        if (p.key == key && t >= p.from && t < p.to) return true;
    return false;
}

bool KeyScript::starts_at(Key key, long long t) const {
    for (const ScriptedPress& p : presses_)
        if (p.key == key && t == p.from) return true;
    return false;
}

Controls KeyScript::controls_at(long long t) const {
    return Controls{held_at(Key::Accelerate, t), held_at(Key::Brake, t), held_at(Key::Left, t),
                    held_at(Key::Right, t)};
}

} // namespace overflight
