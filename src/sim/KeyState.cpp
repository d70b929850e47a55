#include "sim/KeyState.h"

#include <array>

namespace overflight {

namespace {
constexpr std::array<const char*, kKeyCount> kNames = {
    "accelerate", "brake", "left", "right", "fog", "lighting", "wireframe",
    "detail-up", "detail-down", "next-method", "screenshot", "hud", "quit", "shadows", "sun-later", "sun-earlier", "water"};

std::uint8_t bit(Key k) { return std::uint8_t(1u << unsigned(k)); }

Controls controls_of(std::uint8_t bits) {
    return Controls{(bits & bit(Key::Accelerate)) != 0, (bits & bit(Key::Brake)) != 0,
                    (bits & bit(Key::Left)) != 0, (bits & bit(Key::Right)) != 0};
}
} // namespace

const char* key_name(Key k) { return kNames[std::size_t(k)]; }

std::optional<Key> key_from_name(std::string_view name) {
    for (int i = 0; i < kKeyCount; ++i)
        if (name == kNames[std::size_t(i)]) return Key(i);
    return std::nullopt;
}

void KeyState::press(Key k) {
    if (!is_vehicle_key(k)) return;
    held_ |= bit(k);
    latched_ |= bit(k);
}

void KeyState::release(Key k) {
    if (!is_vehicle_key(k)) return;
    held_ &= std::uint8_t(~bit(k));
}

Controls KeyState::sample() {
    const Controls c = controls_of(std::uint8_t(held_ | latched_));
    latched_ = 0;
    return c;
}

Controls KeyState::held() const { return controls_of(held_); }

} // namespace overflight
