// Based on: USGS DEM Standards Part 2 (1992), Record A; Zamri, sec. 3.
#include "io/UsgsDemHeader.h"

#include <algorithm>
#include <cerrno>
#include <cstdlib>
#include <optional>
#include <sstream>

namespace overflight {

namespace {

std::string trim(const std::string& s) {
    const auto b = s.find_first_not_of(" \t\r\n");
    if (b == std::string::npos) return {};
    return s.substr(b, s.find_last_not_of(" \t\r\n") - b + 1);
}

// Columns first..last (1-based, inclusive) of the record.
std::string columns(const std::string& text, std::size_t first, std::size_t last) {
    if (text.size() < first) return {};
    return trim(text.substr(first - 1, last - first + 1));
}

// Fortran D exponents ("0.682D+03") as written by USGS.
bool parse_real(std::string s, double& out) {
    for (char& c : s)
        if (c == 'D' || c == 'd') c = 'E';
    if (s.empty()) return false;
    char* end = nullptr;
    out = std::strtod(s.c_str(), &end);
    return end && *end == '\0';
}

// An integer field: blank, trailing garbage or out of range gives nullopt.
std::optional<long> parse_integer(const std::string& s) {
    if (s.empty()) return std::nullopt;
    errno = 0;
    char* end = nullptr;
    const long v = std::strtol(s.c_str(), &end, 10);
    if (errno == ERANGE || !end || *end != '\0') return std::nullopt;
    return v;
}

std::string format_real(double v) {
    std::ostringstream o;
    o.precision(10);
    o << v;
    return o.str();
}

} // namespace

std::vector<std::pair<std::string, std::string>> usgs_record_a(const std::string& text) {
    std::vector<std::pair<std::string, std::string>> out;
    auto add = [&](const std::string& key, const std::string& value) {
        if (!value.empty()) out.emplace_back(key, value);
    };
    auto integer = [&](std::size_t first, std::size_t last) -> std::string {
        const auto v = parse_integer(columns(text, first, last));
        return v ? std::to_string(*v) : std::string();
    };
    auto real = [&](std::size_t first, std::size_t last) -> std::string {
        double v;
        return parse_real(columns(text, first, last), v) ? format_real(v) : std::string();
    };
    auto coded = [&](std::size_t first, std::size_t last, std::initializer_list<const char*> names) -> std::string {
        const std::string s = integer(first, last);
        if (s.empty()) return s;
        const long v = std::strtol(s.c_str(), nullptr, 10);
        if (v >= 0 && std::size_t(v) < names.size() && *(names.begin()[v])) return s + " (" + names.begin()[v] + ")";
        return s;
    };
    add("USGS_TITLE", columns(text, 1, 40));
    add("USGS_DESCRIPTION", columns(text, 41, 80));
    add("USGS_DEM_LEVEL", integer(145, 150));
    add("USGS_ELEVATION_PATTERN", coded(151, 156, {"", "regular", "random"}));
    add("USGS_PLANIMETRIC_SYSTEM", coded(157, 162, {"geographic", "UTM", "state plane"}));
    add("USGS_ZONE", integer(163, 168));
    add("USGS_PLANIMETRIC_UNITS", coded(529, 534, {"radians", "feet", "metres", "arc-seconds"}));
    add("USGS_ELEVATION_UNITS", coded(535, 540, {"", "feet", "metres"}));
    static const char* corners[4] = {"SW", "NW", "NE", "SE"};
    for (int c = 0; c < 4; ++c) {
        const std::size_t x0 = 547 + std::size_t(c) * 48;
        const std::string x = real(x0, x0 + 23), y = real(x0 + 24, x0 + 47);
        if (!x.empty() && !y.empty()) add(std::string("USGS_CORNER_") + corners[c], x + ", " + y);
    }
    add("USGS_MIN_ELEVATION", real(739, 762));
    add("USGS_MAX_ELEVATION", real(763, 786));
    add("USGS_ANGLE", real(787, 810));
    add("USGS_ACCURACY_CODE", integer(811, 816));
    const std::string rx = real(817, 828), ry = real(829, 840), rz = real(841, 852);
    if (!rx.empty() && !ry.empty() && !rz.empty()) add("USGS_RESOLUTION", rx + ", " + ry + ", " + rz);
    add("USGS_ROWS", integer(853, 858));
    add("USGS_PROFILES", integer(859, 864));
    return out;
}

long usgs_profile_count(const std::string& text) {
    const auto v = parse_integer(columns(text, 859, 864));
    return v && *v >= 0 ? *v : -1;
}

long long usgs_minimum_file_size(long profiles) {
    // Record A takes at least the 864 columns up to element 16.
    return 864 + std::max(0L, profiles) * kUsgsRecordBHeaderBytes;
}

} // namespace overflight
