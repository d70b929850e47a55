#pragma once
// A recorded flight: per frame, the camera every renderer shares (DESIGN
// sec. 2) and the vehicle state and keys that produced it, so that
// `fly --replay` can render exactly the same camera path headless. The text
// form is CSV with one header line:
//
//   frame,time,eye_x,eye_y,eye_z,heading,pitch,x,z,velocity,vehicle_heading,accelerate,brake,left,right
//
// frame: 0, 1, 2, ... in order; time: seconds since the start; eye_*, heading,
// pitch: the camera (degrees); x, z, velocity, vehicle_heading: the hovercraft
// state (CMSC 23700 project 2a sec. 3.2); the last four columns are 0/1 for the vehicle keys
// held in that frame. Numbers are written in shortest round-trip form
// (std::to_chars), so parse(format(r)) == r bit for bit. Lines starting with
// '#' and blank lines are ignored. File I/O lives in io/FlightRecordFile.h.
#include "sim/KeyState.h"

#include <glm/vec3.hpp>

#include <string>
#include <string_view>
#include <vector>

namespace overflight {

struct FlightFrame {
    long long frame = 0;
    double time = 0;
    glm::dvec3 eye{0.0};
    double heading = 0, pitch = 0; // camera, degrees
    double x = 0, z = 0, velocity = 0, vehicle_heading = 0;
    Controls keys;
    friend bool operator==(const FlightFrame&, const FlightFrame&) = default;
};

struct FlightRecord {
    std::vector<FlightFrame> frames;
    friend bool operator==(const FlightRecord&, const FlightRecord&) = default;
};

// The header line, without newline.
const char* flight_record_header();

// One CSV line (no newline) and the whole text (header + one line per frame).
std::string format_flight_frame(const FlightFrame& f);
std::string format_flight_record(const FlightRecord& record);

// Parses the text form. `source` names the file in errors: throws
// Error(source, "line N: ...") for a wrong header, a wrong column count, a
// number that does not parse or is not finite, a camera the renderers refuse
// (Camera::validate: |pitch| >= 89), a key column other than 0/1, frames out
// of order, or no frames at all.
FlightRecord parse_flight_record(std::string_view text, const std::string& source);

} // namespace overflight
