#include "sim/FlightRecord.h"

#include "core/Camera.h"
#include "core/Error.h"

#include <array>
#include <charconv>
#include <cmath>

namespace overflight {

namespace {

constexpr int kColumns = 15;

void append_number(std::string& out, double v) {
    std::array<char, 32> buf{};
    const auto r = std::to_chars(buf.data(), buf.data() + buf.size(), v);
    out.append(buf.data(), r.ptr);
}

void append_number(std::string& out, long long v) {
    std::array<char, 24> buf{};
    const auto r = std::to_chars(buf.data(), buf.data() + buf.size(), v);
    out.append(buf.data(), r.ptr);
}

// Splits one CSV line at commas (no quoting: every field is a number).
int split(std::string_view line, std::array<std::string_view, kColumns>& fields) {
    int n = 0;
    std::size_t start = 0;
    while (true) {
        const auto comma = line.find(',', start);
        const std::string_view field = line.substr(start, comma == std::string_view::npos ? line.npos : comma - start);
        if (n < kColumns) fields[std::size_t(n)] = field;
        ++n;
        if (comma == std::string_view::npos) return n;
        start = comma + 1;
    }
}

} // namespace

const char* flight_record_header() {
    return "frame,time,eye_x,eye_y,eye_z,heading,pitch,x,z,velocity,vehicle_heading,accelerate,brake,left,right";
}

std::string format_flight_frame(const FlightFrame& f) {
    std::string s;
    s.reserve(200);
    append_number(s, f.frame);
    for (double v : {f.time, f.eye.x, f.eye.y, f.eye.z, f.heading, f.pitch, f.x, f.z, f.velocity,
                     f.vehicle_heading}) {
        s += ',';
        append_number(s, v);
    }
    for (bool k : {f.keys.accelerate, f.keys.brake, f.keys.left, f.keys.right}) s += k ? ",1" : ",0";
    return s;
}

std::string format_flight_record(const FlightRecord& record) {
    std::string s = flight_record_header();
    s += '\n';
    for (const FlightFrame& f : record.frames) {
        s += format_flight_frame(f);
        s += '\n';
    }
    return s;
}

FlightRecord parse_flight_record(std::string_view text, const std::string& source) {
    FlightRecord record;
    bool header_seen = false;
    long long line_no = 0;
    std::size_t pos = 0;
    std::array<std::string_view, kColumns> fields;
    while (pos < text.size()) {
        const auto nl = text.find('\n', pos);
        std::string_view line = text.substr(pos, nl == std::string_view::npos ? text.npos : nl - pos);
        pos = nl == std::string_view::npos ? text.size() : nl + 1;
        ++line_no;
        if (!line.empty() && line.back() == '\r') line.remove_suffix(1); // files edited on Windows
        if (line.empty() || line.front() == '#') continue;
        const std::string where = "line " + std::to_string(line_no) + ": ";
        if (!header_seen) {
            if (line != flight_record_header())
                throw Error(source, where + "not a flight record (expected the header '" +
                                        flight_record_header() + "')");
            header_seen = true;
            continue;
        }
        const int n = split(line, fields);
        if (n != kColumns)
            throw Error(source, where + std::to_string(n) + " columns, expected " + std::to_string(kColumns));
        FlightFrame f;
        {
            const std::string_view t = fields[0];
            const auto [end, ec] = std::from_chars(t.data(), t.data() + t.size(), f.frame);
            if (ec != std::errc() || end != t.data() + t.size() || t.empty())
                throw Error(source, where + "frame '" + std::string(t) + "' is not a whole number");
        }
        static constexpr std::array<const char*, 10> kNames = {
            "time", "eye_x", "eye_y", "eye_z", "heading", "pitch", "x", "z", "velocity", "vehicle_heading"};
        std::array<double*, 10> dst = {&f.time, &f.eye.x, &f.eye.y, &f.eye.z, &f.heading,
                                       &f.pitch, &f.x, &f.z, &f.velocity, &f.vehicle_heading};
        for (std::size_t i = 0; i < dst.size(); ++i) {
            const std::string_view t = fields[i + 1];
            const auto [end, ec] = std::from_chars(t.data(), t.data() + t.size(), *dst[i]);
            if (ec != std::errc() || end != t.data() + t.size() || t.empty() || !std::isfinite(*dst[i]))
                throw Error(source, where + kNames[i] + " '" + std::string(t) + "' is not a finite number");
        }
        std::array<bool*, 4> keys = {&f.keys.accelerate, &f.keys.brake, &f.keys.left, &f.keys.right};
        for (std::size_t i = 0; i < keys.size(); ++i) {
            const std::string_view t = fields[i + 11];
            if (t != "0" && t != "1")
                throw Error(source, where + key_name(Key(i)) + " must be 0 or 1, not '" + std::string(t) + "'");
            *keys[i] = t == "1";
        }
        // The camera must be one every renderer accepts, so that a replay
        // fails here, naming the line, rather than in the middle of rendering.
        Camera camera;
        camera.eye = f.eye;
        camera.heading = f.heading;
        camera.pitch = f.pitch;
        try {
            camera.validate();
        } catch (const Error& e) {
            throw Error(source, where + e.problem());
        }
        if (!record.frames.empty() && f.frame <= record.frames.back().frame)
            throw Error(source, where + "frame " + std::to_string(f.frame) + " is not after frame " +
                                    std::to_string(record.frames.back().frame));
        record.frames.push_back(f);
    }
    if (!header_seen) throw Error(source, "empty file, not a flight record");
    if (record.frames.empty()) throw Error(source, "flight record has no frames");
    return record;
}

} // namespace overflight
