// The demo island: its relief (DemoRelief.h: ridged multifractal noise with
// domain warping and an island falloff) quantised into heights, a batch of
// samples of a row at a time, colored by elevation and slope, and the village
// and objects placed on it.
#include "core/DemoIsland.h"

#include "core/DemoRelief.h"
#include "core/Error.h"
#include "core/Parallel.h"
#include "core/Shading.h"

#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>

#include <algorithm>
#include <cmath>
#include <string>

namespace overflight {
namespace {

constexpr float kSeaLevel = 0.0f;   // world metres
constexpr float kSeaFloor = -60.0f; // y0: the lowest representable height
constexpr float kVScale = 0.05f;    // 5 cm height steps: 65535 steps cover 3.2 km

// A flat, dry spot for the village: the flattest of a few deterministic candidates on land.
glm::vec2 find_village(const Terrain& t) {
    glm::vec2 best{t.width() * 0.5f, t.depth() * 0.5f};
    float best_score = 1e30f;
    for (int k = 0; k < 400; ++k) {
        const float s = 0.2f + 0.6f * float(demo_lattice_hash(std::uint32_t(k), 1u, 77u) & 0xFFFF) / 65535.0f;
        const float u = 0.2f + 0.6f * float(demo_lattice_hash(std::uint32_t(k), 2u, 77u) & 0xFFFF) / 65535.0f;
        const float x = s * t.width(), z = u * t.depth();
        const float h = t.height_bilinear(x, z);
        if (h < 40.0f || h > 500.0f) continue;
        const glm::vec3 n = t.normal(x, z);
        float rough = 0;
        for (float d = -60; d <= 60; d += 30)
            rough += std::abs(t.height_bilinear(x + d, z) - h) + std::abs(t.height_bilinear(x, z + d) - h);
        const float score = (1.0f - n.y) * 1000.0f + rough;
        if (score < best_score) { best_score = score; best = {x, z}; }
    }
    return best;
}

} // namespace

DataSet make_demo_island(const DemoOptions& options) {
    const int n = options.size;
    if (n < 33 || n > 16385 || !is_pow2_plus1(n))
        throw Error("demo", "size " + std::to_string(n) + " is not 2^n+1 in 33..16385");

    DataSet ds;
    ds.terrain = Terrain(n, n, options.h_scale, kVScale, kSeaFloor);
    Terrain& t = ds.terrain;
    // Octaves follow the resolution so larger islands gain detail, not just size.
    const int octaves = std::clamp(int(std::log2(float(n - 1))) - 1, 4, 13);
    // A row's last batch repeats its last column in the lanes past the edge.
    parallel::for_each_index(0, n, [&](int row) {
        float s[kDemoReliefLanes], t_row[kDemoReliefLanes], relief[kDemoReliefLanes];
        std::fill_n(t_row, kDemoReliefLanes, float(row) / float(n - 1));
        for (int col0 = 0; col0 < n; col0 += kDemoReliefLanes) {
            for (int i = 0; i < kDemoReliefLanes; ++i) s[i] = float(std::min(col0 + i, n - 1)) / float(n - 1);
            demo_relief(s, t_row, octaves, options.seed, relief);
            for (int col = col0; col < std::min(col0 + kDemoReliefLanes, n); ++col) {
                const float h = std::max(relief[col - col0], kSeaLevel - 35.0f);
                t.raw(row, col) = std::uint16_t(std::clamp(std::lround((h - kSeaFloor) / kVScale), 0L, 65535L));
            }
        }
    });
    shade_by_elevation(t, kSeaLevel);
    // Steep slopes are bare rock whatever their height.
    parallel::for_each_index(0, n, [&](int row) {
        for (int col = 0; col < n; ++col) {
            const float h = t.sample_height(row, col);
            if (h < kSeaLevel + 3.0f) continue;
            const float steep = std::clamp((0.82f - t.sample_normal(row, col).y) * 5.0f, 0.0f, 1.0f);
            Rgb8& c = t.color(row, col);
            const float g = 0.6f * float(c.r + c.g + c.b) / 3.0f + 30.0f;
            c = Rgb8{std::uint8_t(c.r + (g * 1.05f - c.r) * steep), std::uint8_t(c.g + (g - c.g) * steep),
                     std::uint8_t(c.b + (g * 0.95f - c.b) * steep)};
        }
    });
    // The sea is a flat surface at sea level (the relief below it is only colour).
    const auto sea = std::uint16_t(std::lround((kSeaLevel - kSeaFloor) / kVScale));
    for (auto& h : t.heights()) h = std::max(h, sea);

    ds.environment.fog_density = 1.2f / (t.width() * 1.0f);
    ds.environment.sun_dir = glm::normalize(glm::vec3(-0.4f, 0.7f, -0.6f));

    const glm::vec2 v = find_village(t);
    ds.start.given = true;
    ds.start.x = v.x;
    ds.start.z = v.y;
    // Face the island centre so the first view looks across the mountains.
    ds.start.heading = std::atan2(t.width() * 0.5 - v.x, t.depth() * 0.5 - v.y) * 180.0 / 3.14159265358979;

    const double hr = glm::radians(ds.start.heading);
    const glm::dvec2 fwd{std::sin(hr), std::cos(hr)}, side{-std::cos(hr), std::sin(hr)};
    const glm::dvec2 base{v.x, v.y};
    const double cell = t.h_scale();
    const Rgb8 walls[] = {{225, 215, 190}, {200, 90, 70}, {235, 235, 230}, {190, 170, 120}};
    for (int k = 0; k < 6; ++k) {
        SceneObject house;
        house.kind = ObjectKind::House;
        const glm::dvec2 p = base + fwd * (6.0 * cell + 4.0 * cell * (k / 3)) + side * (4.0 * cell * (k % 3 - 1));
        house.x = p.x;
        house.z = p.y;
        house.width = 12 + 2 * (k % 2);
        house.depth = 9;
        house.height = 7;
        house.heading = ds.start.heading + 15.0 * (k % 3);
        house.color = walls[k % 4];
        ds.scene.objects.push_back(house);
    }
    SceneObject vehicle;
    vehicle.kind = ObjectKind::Vehicle;
    vehicle.x = base.x + fwd.x * 2 * cell;
    vehicle.z = base.y + fwd.y * 2 * cell;
    vehicle.width = 3;
    vehicle.height = 2;
    vehicle.depth = 5;
    vehicle.heading = ds.start.heading;
    vehicle.color = {230, 180, 30};
    ds.scene.objects.push_back(vehicle);
    SceneObject tower_box; // a water tower, visible from afar
    tower_box.kind = ObjectKind::Box;
    tower_box.x = base.x - side.x * 9 * cell;
    tower_box.z = base.y - side.y * 9 * cell;
    tower_box.width = tower_box.depth = 8;
    tower_box.height = 30;
    tower_box.color = {180, 40, 40};
    ds.scene.objects.push_back(tower_box);

    TransmissionLine line; // from the village towards the centre of the island
    for (int k = 0; k < 5; ++k) {
        const glm::dvec2 p = base + side * (7.0 * cell) + fwd * (double(k) * 25.0 * cell);
        line.points.push_back(glm::clamp(p, glm::dvec2(0.0), glm::dvec2(t.width(), t.depth())));
    }
    line.height = 35;
    line.sag = 5;
    ds.scene.lines.push_back(line);

    ds.info.source = "demo";
    ds.info.kind = "demo";
    ds.info.driver = "procedural";
    ds.info.color_source = "procedural (elevation ramp, slope rock, hillshade)";
    ds.info.source_rows = ds.info.source_cols = n;
    ds.info.metadata = {{"seed", std::to_string(options.seed)}, {"octaves", std::to_string(octaves)}};
    return ds;
}

} // namespace overflight
