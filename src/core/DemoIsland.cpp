// Based on: Musgrave's ridged multifractal (Texturing & Modeling, ch. 16) over
// gradient noise (Perlin 2002), with domain warping (Quilez) for the drainage-
// like ridges, and an island falloff. Deterministic: the noise is built on an
// integer hash, not on std:: distributions whose output differs by library.
#include "core/DemoIsland.h"

#include "core/Error.h"
#include "core/Parallel.h"
#include "core/Shading.h"

#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

namespace overflight {
namespace {

constexpr float kSeaLevel = 0.0f;   // world metres
constexpr float kPeak = 1400.0f;    // highest relief before the falloff
constexpr float kSeaFloor = -60.0f; // y0: the lowest representable height
constexpr float kVScale = 0.05f;    // 5 cm height steps: 65535 steps cover 3.2 km

std::uint32_t hash(std::uint32_t x, std::uint32_t y, std::uint32_t seed) {
    std::uint32_t h = seed * 0x9E3779B9u ^ x * 0x85EBCA6Bu ^ y * 0xC2B2AE35u;
    h ^= h >> 16; h *= 0x7FEB352Du;
    h ^= h >> 15; h *= 0x846CA68Bu;
    h ^= h >> 16;
    return h;
}

// The unit gradients of gradient_noise, one per 16-bit angle: a lattice
// point's gradient is picked by 16 bits of its hash, so 65536 cosines and sines
// computed once (the same float expressions, so the same bits) stand for the
// 140 per height sample that the island's octaves would otherwise compute
// (they were three quarters of its generation time).
struct Gradient {
    float cos, sin;
};
const std::vector<Gradient>& gradients() {
    static const std::vector<Gradient> table = [] {
        std::vector<Gradient> g(65536);
        for (std::uint32_t k = 0; k < 65536; ++k) {
            const float a = float(k) * (6.28318530718f / 65536.0f);
            g[k] = {std::cos(a), std::sin(a)};
        }
        return g;
    }();
    return table;
}

// 2D gradient noise in about [-1, 1] with quintic fade.
float gradient_noise(float x, float y, std::uint32_t seed) {
    const float fx = std::floor(x), fy = std::floor(y);
    const auto ix = std::uint32_t(std::int32_t(fx)), iy = std::uint32_t(std::int32_t(fy));
    const float tx = x - fx, ty = y - fy;
    const Gradient* table = gradients().data();
    auto grad = [&](std::uint32_t cx, std::uint32_t cy, float dx, float dy) {
        const Gradient& g = table[hash(cx, cy, seed) & 0xFFFFu];
        return g.cos * dx + g.sin * dy;
    };
    const float n00 = grad(ix, iy, tx, ty), n10 = grad(ix + 1, iy, tx - 1, ty);
    const float n01 = grad(ix, iy + 1, tx, ty - 1), n11 = grad(ix + 1, iy + 1, tx - 1, ty - 1);
    auto fade = [](float t) { return t * t * t * (t * (t * 6 - 15) + 10); };
    const float u = fade(tx), v = fade(ty);
    const float a = n00 + (n10 - n00) * u, b = n01 + (n11 - n01) * u;
    return 1.41421356f * (a + (b - a) * v);
}

float fbm(float x, float y, int octaves, std::uint32_t seed) {
    float sum = 0, amp = 0.5f, freq = 1;
    for (int o = 0; o < octaves; ++o) {
        sum += amp * gradient_noise(x * freq, y * freq, seed + std::uint32_t(o));
        amp *= 0.5f;
        freq *= 2.03f;
    }
    return sum;
}

// Ridged multifractal: sharp crests where the noise crosses zero, each octave
// weighted by the previous one so valleys stay smooth (erosion-like).
float ridged(float x, float y, int octaves, std::uint32_t seed) {
    float sum = 0, weight = 1, amp = 0.5f, freq = 1, norm = 0;
    for (int o = 0; o < octaves; ++o) {
        float n = 1.0f - std::abs(gradient_noise(x * freq, y * freq, seed + 101u + std::uint32_t(o)));
        n *= n;
        n *= weight;
        weight = std::clamp(n * 2.0f, 0.0f, 1.0f);
        sum += n * amp;
        norm += amp;
        amp *= 0.5f;
        freq *= 2.0f;
    }
    return sum / norm;
}

// Relief in metres at normalised position (s, t) in [0,1]^2.
float relief(float s, float t, int octaves, std::uint32_t seed) {
    // Domain warp bends the ridges into drainage-like patterns.
    const float wx = fbm(s * 3.0f, t * 3.0f, 4, seed + 7u);
    const float wy = fbm(s * 3.0f + 5.2f, t * 3.0f + 1.3f, 4, seed + 11u);
    const float x = s * 6.0f + 0.8f * wx, y = t * 6.0f + 0.8f * wy;
    const float mountains = ridged(x, y, octaves, seed);
    const float hills = 0.5f + 0.5f * fbm(x * 1.7f, y * 1.7f, octaves, seed + 31u);
    // Island falloff: distance from the centre, perturbed so the coast is ragged.
    const float dx = s - 0.5f, dy = t - 0.5f;
    const float r = std::sqrt(dx * dx + dy * dy) * 2.0f + 0.25f * fbm(s * 4.0f, t * 4.0f, 5, seed + 53u);
    const float island = std::clamp(1.15f - r * 1.2f, -1.0f, 1.0f);
    const float land = island > 0 ? std::pow(island, 0.8f) : island;
    return land * (0.75f * mountains + 0.25f * hills) * kPeak + (land - 0.12f) * 220.0f;
}

// A flat, dry spot for the village: the flattest of a few deterministic candidates on land.
glm::vec2 find_village(const Terrain& t) {
    glm::vec2 best{t.width() * 0.5f, t.depth() * 0.5f};
    float best_score = 1e30f;
    for (int k = 0; k < 400; ++k) {
        const float s = 0.2f + 0.6f * float(hash(std::uint32_t(k), 1u, 77u) & 0xFFFF) / 65535.0f;
        const float u = 0.2f + 0.6f * float(hash(std::uint32_t(k), 2u, 77u) & 0xFFFF) / 65535.0f;
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
    parallel::for_each_index(0, n, [&](int row) {
        for (int col = 0; col < n; ++col) {
            float h = relief(float(col) / float(n - 1), float(row) / float(n - 1), octaves, options.seed);
            h = std::max(h, kSeaLevel - 35.0f);
            t.raw(row, col) = std::uint16_t(std::clamp(std::lround((h - kSeaFloor) / kVScale), 0L, 65535L));
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
