#pragma once
// Based on: CMSC 23700 project 2a, "sports utility hovercraft" (CMSC 23700 project 2a),
// sec. 3.1 (controls) and its footnote 1: the arrow keys are SAMPLED by the
// 100 Hz physics rather than acted on per event, and "any transient keystroke
// gets sampled at least once in the physics model". KeyState is that sampler:
// it holds which keys are down and latches presses until a step has seen them.
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

namespace overflight {

// Every key the viewer reacts to (CMSC 23700 project 2a sec. 3.1 plus the Tab, P, H).
// The first four are sampled by the physics; the rest are one-shot commands.
enum class Key : std::uint8_t {
    Accelerate, // UP arrow
    Brake,      // DOWN arrow
    Left,       // LEFT arrow: heading increases
    Right,      // RIGHT arrow: heading decreases
    Fog,        // f
    Lighting,   // 1
    Wireframe,  // W
    DetailUp,   // +  (level of detail x sqrt 2)
    DetailDown, // _  (level of detail / sqrt 2)
    NextMethod, // Tab
    Screenshot, // P
    Hud,        // H
    Quit,       // q
    Shadows,    // s  (the terrain's cast shadows)
    SunLater,   // t  (the sun half an hour later along its day arc)
    SunEarlier, // T  (half an hour earlier)
    Water,      // o  (the water surface on/off)
};
inline constexpr int kKeyCount = 17;

// The name used on the command line (`--press accelerate:0-100`) and in records:
// accelerate, brake, left, right, fog, lighting, wireframe, detail-up,
// detail-down, next-method, screenshot, hud, quit, shadows, sun-later, sun-earlier, water.
const char* key_name(Key k);
// Inverse of key_name; nullopt for an unknown name.
std::optional<Key> key_from_name(std::string_view name);
// True for the four keys the physics samples.
constexpr bool is_vehicle_key(Key k) { return std::uint8_t(k) <= std::uint8_t(Key::Right); }

// What one physics step sees: the paper's "if accelerating / braking / turning".
struct Controls {
    bool accelerate = false;
    bool brake = false;
    bool left = false;
    bool right = false;
    friend bool operator==(const Controls&, const Controls&) = default;
};

// Sampled state of the four vehicle keys. press()/release() are fed from key
// events (a repeated press of a key already down changes nothing, so key
// repeat is ignored whether or not the window system filters it); sample() is
// called once per physics step and reports a key as down if it is held now OR
// was pressed at any time since the previous sample, so a tap shorter than a
// step is still seen by exactly one step.
class KeyState {
public:
    void press(Key k);
    void release(Key k);
    // Keys down now or pressed since the last sample; clears the latch.
    Controls sample();
    // Keys down now, without touching the latch (for the HUD).
    Controls held() const;
    void clear() { held_ = 0; latched_ = 0; }

private:
    std::uint8_t held_ = 0;    // bit per vehicle key
    std::uint8_t latched_ = 0; // pressed since the last sample
};

} // namespace overflight
