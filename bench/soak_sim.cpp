// Checker for the `sim` soak (scripts/soak_sim.sh; not a benchmark, not in
// CI): reads the CSV `overflight sim TERRAIN ...` prints on stdin and checks,
// for every step, the properties DESIGN sec. 8 asks of the vehicle: every
// number finite, the vehicle inside the map, and above every surface the
// renderers draw (the bilinear surface and the mesh triangles; CMSC 23700
// project 2a, "sports utility hovercraft", footnote 2: the vehicle rides
// `altitude` above the terrain). Steps must run 0, 1, 2, ...
//
//   overflight sim TERRAIN --steps N ... | soak_sim TERRAIN [--demo-size N] [--steps N]
//
// Prints one summary line; exits 1 naming the first step that breaks a
// property.
#include "core/Error.h"
#include "io/LoadTerrain.h"
#include "sim/Hovercraft.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <string_view>

using namespace overflight;

namespace {

// The six fields of one CSV row; false if the row is not six numbers.
bool parse_row(std::string_view line, long long& step, double (&v)[5]) {
    const char* p = line.data();
    const char* end = line.data() + line.size();
    auto r = std::from_chars(p, end, step);
    if (r.ec != std::errc() || r.ptr == end || *r.ptr != ',') return false;
    p = r.ptr + 1;
    for (int i = 0; i < 5; ++i) {
        const auto f = std::from_chars(p, end, v[i]);
        if (f.ec != std::errc()) return false;
        p = f.ptr;
        if (i < 4) {
            if (p == end || *p != ',') return false;
            ++p;
        }
    }
    return p == end;
}

// The surfaces the renderers draw at (x, z): the higher of the bilinear
// surface and the mesh triangle. The bilinear one is evaluated at float
// positions; x and z read back from 6 decimals may round to a float next to
// the one the simulation used, and on a 10 km map one float step (1 mm)
// times the slope moves the surface by millimetres: take the lowest of the
// neighbouring floats, so only a real dip below the surface fails.
double lowest_surface(const Terrain& t, double x, double z) {
    double lowest = INFINITY;
    for (float xf : {std::nextafter(float(x), -INFINITY), float(x), std::nextafter(float(x), INFINITY)})
        for (float zf : {std::nextafter(float(z), -INFINITY), float(z), std::nextafter(float(z), INFINITY)})
            lowest = std::min(lowest, std::max(double(t.height_bilinear(xf, zf)), mesh_height(t, xf, zf)));
    return lowest;
}

int fail(long long step, const std::string& what) {
    std::fprintf(stderr, "soak_sim: step %lld: %s\n", step, what.c_str());
    return 1;
}

} // namespace

int main(int argc, char** argv) {
    if (argc < 2) {
        std::fprintf(stderr, "usage: overflight sim TERRAIN ... | soak_sim TERRAIN [--demo-size N] [--steps N]\n");
        return 2;
    }
    LoadOptions load;
    long long expected_steps = -1;
    for (int i = 2; i + 1 < argc; i += 2) {
        if (std::strcmp(argv[i], "--demo-size") == 0) load.demo_size = std::atoi(argv[i + 1]);
        else if (std::strcmp(argv[i], "--steps") == 0) expected_steps = std::atoll(argv[i + 1]);
    }
    DataSet data;
    try {
        data = load_terrain(argv[1], load);
    } catch (const Error& e) {
        std::fprintf(stderr, "soak_sim: %s\n", e.what());
        return 1;
    }
    const Terrain& t = data.terrain;
    const double altitude = HovercraftParams{}.altitude;
    // y and the heights are rounded to 6 decimals and float precision.
    const double tolerance = 1e-4;

    static char buf[1 << 16];
    long long rows = 0;
    double min_clearance = INFINITY, max_speed = 0;
    long long near_edge = 0;
    bool header = true;
    std::size_t n;
    std::string pending;
    while ((n = std::fread(buf, 1, sizeof buf, stdin)) > 0) {
        pending.append(buf, n);
        std::size_t start = 0, nl;
        while ((nl = pending.find('\n', start)) != std::string::npos) {
            const std::string_view row(pending.data() + start, nl - start);
            start = nl + 1;
            if (header) {
                if (row != "step,x,z,y,velocity,heading") return fail(-1, "not sim's CSV header: " + std::string(row));
                header = false;
                continue;
            }
            long long step = 0;
            double v[5];
            if (!parse_row(row, step, v)) return fail(rows, "not six numbers: " + std::string(row));
            const double x = v[0], z = v[1], y = v[2], speed = v[3], heading = v[4];
            if (step != rows) return fail(rows, "row numbered " + std::to_string(step));
            for (double d : v)
                if (!std::isfinite(d)) return fail(step, "not finite: " + std::string(row));
            if (!(x >= 0 && z >= 0 && x <= t.width() && z <= t.depth()))
                return fail(step, "outside the map: " + std::string(row));
            if (speed < 0) return fail(step, "negative speed: " + std::string(row));
            if (!(heading >= 0 && heading < 360)) return fail(step, "heading outside [0, 360): " + std::string(row));
            const double clearance = y - ground_height(t, x, z);
            if (y - lowest_surface(t, x, z) < altitude - tolerance)
                return fail(step, "below altitude: y " + std::to_string(y) + ", surface " +
                                      std::to_string(lowest_surface(t, x, z)));
            min_clearance = std::min(min_clearance, clearance);
            max_speed = std::max(max_speed, speed);
            // A bounce mirrors the position back inside: count the rows near
            // an edge, to show the runs reached it.
            near_edge += std::min({x, z, t.width() - x, t.depth() - z}) < 1.0;
            ++rows;
        }
        pending.erase(0, start);
    }
    if (std::ferror(stdin)) return fail(rows, "read error on stdin");
    if (!pending.empty()) return fail(rows, "last row has no newline (output cut short?)");
    if (expected_steps >= 0 && rows != expected_steps)
        return fail(rows, "expected " + std::to_string(expected_steps) + " rows");
    std::printf("soak_sim: %s: %lld steps ok; min clearance %.4f (altitude %.1f), max speed %.3f, "
                "%lld rows within 1 m of an edge\n",
                argv[1], rows, min_clearance, altitude, max_speed, near_edge);
    return 0;
}
