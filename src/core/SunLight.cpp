// Based on: CMSC 23700 hovercraft project sec. 4.1 (sun and ambient light). See SunLight.h.
#include "core/SunLight.h"

#include "core/Parallel.h"

#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>
#include <glm/gtc/constants.hpp>

#include <algorithm>
#include <cmath>

namespace overflight {

namespace {

glm::vec3 unit_sun(const Environment& env) {
    return glm::length(env.sun_dir) > 0 ? glm::normalize(env.sun_dir) : glm::vec3(0, 1, 0);
}

bool same_light(const Environment& a, const Environment& b) {
    return a.sun_dir == b.sun_dir && a.sun_color == b.sun_color && a.ambient == b.ambient && a.shadows == b.shadows &&
           a.baked == b.baked;
}

std::uint8_t channel(std::uint8_t albedo, float light) {
    const float v = float(albedo) * light + 0.5f;
    return std::uint8_t(std::clamp(v, 0.0f, 255.0f));
}

} // namespace

namespace {
void light_samples(const Terrain& t, const PackedNormals& normals, const Environment& env, const ShadowCeiling* shadow,
                   const std::uint8_t* mask, std::vector<Rgb8>& out, std::vector<Rgb8>* other, LightOutput output);
} // namespace

glm::vec3 sun_direction(double azimuth_deg, double elevation_deg) {
    const double az = glm::radians(azimuth_deg), el = glm::radians(elevation_deg);
    return glm::vec3(float(std::sin(az) * std::cos(el)), float(std::sin(el)), float(-std::cos(az) * std::cos(el)));
}

SunAngles sun_angles(const glm::vec3& sun_dir) {
    const glm::dvec3 d = glm::normalize(glm::dvec3(sun_dir));
    SunAngles a;
    a.elevation = glm::degrees(std::asin(std::clamp(d.y, -1.0, 1.0)));
    a.azimuth = glm::degrees(std::atan2(d.x, -d.z));
    if (a.azimuth < 0) a.azimuth += 360.0;
    return a;
}

glm::vec3 sun_at_hour(double hour) {
    // Azimuth sweeps east -> south -> west by day and goes on round the north by night.
    const double day = (hour - 6.0) / 12.0; // 0 at sunrise, 1 at sunset
    return sun_direction(std::fmod(90.0 + 180.0 * day + 360.0, 360.0), kNoonElevation * std::sin(glm::pi<double>() * day));
}

double hour_of_sun(const glm::vec3& sun_dir) {
    // By day the arc's azimuth runs from 90 (east) to 270 (west); a northern
    // sun is taken to the nearer end.
    const double az = std::clamp(sun_angles(sun_dir).azimuth, 90.0, 270.0);
    return 6.0 + 12.0 * (az - 90.0) / 180.0;
}

void bake_lighting(Environment& env) { env.baked = true; }

bool lighting_is_baked(const Environment& env) { return env.baked; }

glm::vec3 sample_light(const Environment& env, const glm::vec3& n, bool lit) {
    const glm::vec3 sun = unit_sun(env);
    const float lambert = sun.y > 0 && lit ? std::max(glm::dot(n, sun), 0.0f) : 0.0f;
    return env.ambient + env.sun_color * lambert;
}

void light_colors(const Terrain& t, const PackedNormals& normals, const Environment& env, const ShadowCeiling* shadow,
                  std::vector<Rgb8>& out, LightOutput output) {
    light_samples(t, normals, env, shadow, nullptr, out, nullptr, output);
}

void light_colors(const Terrain& t, const PackedNormals& normals, const Environment& env,
                  const std::vector<std::uint8_t>& shadow_mask, std::vector<Rgb8>& out, LightOutput output) {
    light_samples(t, normals, env, nullptr, shadow_mask.data(), out, nullptr, output);
}

void light_colors(const Terrain& t, const PackedNormals& normals, const Environment& env,
                  const std::vector<std::uint8_t>& shadow_mask, std::vector<Rgb8>& out, std::vector<Rgb8>& other,
                  LightOutput output) {
    light_samples(t, normals, env, nullptr, shadow_mask.data(), out, &other, output);
}

namespace {

// One row of light_samples: its inputs and scratch.
struct LightRow {
    int cols = 0;
    glm::vec3 l{0.0f};
    float vs = 1, y0 = 0;
    bool light_only = false;
    float amb[3] = {}, sun_rgb[3] = {};
    const std::uint32_t* n = nullptr;
    const std::uint16_t* raw = nullptr;
    const std::uint8_t* albedo = nullptr;
    const float* ceiling = nullptr;
    const std::uint8_t* mask = nullptr;
    float* L = nullptr;  // cols
    float* LL = nullptr; // 3 cols
    std::uint8_t* dst = nullptr;
    std::uint8_t* other = nullptr; // with `mask`: the colors with the mask flipped (null: none)
};

// The light per channel of the Lambert terms L, then Rgb8 as bytes into dst:
// plain loops, which vectorize.
[[gnu::always_inline]] inline void light_bytes(const LightRow& r, const float* L, std::uint8_t* dst) {
    static_assert(sizeof(Rgb8) == 3);
    const int cols = r.cols;
    const std::size_t count = 3 * std::size_t(cols);
    float* LL = r.LL;
    for (int col = 0; col < cols; ++col) {
        LL[3 * col] = r.amb[0] + r.sun_rgb[0] * L[col];
        LL[3 * col + 1] = r.amb[1] + r.sun_rgb[1] * L[col];
        LL[3 * col + 2] = r.amb[2] + r.sun_rgb[2] * L[col];
    }
    if (r.light_only)
        for (std::size_t i = 0; i < count; ++i) dst[i] = channel(128, LL[i]);
    else
        for (std::size_t i = 0; i < count; ++i) dst[i] = channel(r.albedo[i], LL[i]);
}

// Passes over the row, each without branches, so that each vectorizes.
[[gnu::always_inline]] inline void light_row_body(const LightRow& r) {
    const int cols = r.cols;
    const glm::vec3 l = r.l;
    float* L = r.L;
    for (int col = 0; col < cols; ++col) {
        const std::uint32_t p = r.n[col];
        L[col] = std::max(PackedNormals::x_of(p) * l.x + PackedNormals::y_of(p) * l.y + PackedNormals::z_of(p) * l.z, 0.0f);
    }
    if (r.other) { // the flipped light first, while L holds the sun's term unmasked
        float* F = L + cols;
        for (int col = 0; col < cols; ++col) F[col] = r.mask[col] ? L[col] : 0.0f;
        light_bytes(r, F, r.other);
    }
    if (r.ceiling) {
        for (int col = 0; col < cols; ++col) L[col] = r.vs * float(r.raw[col]) + r.y0 < r.ceiling[col] ? 0.0f : L[col];
    } else if (r.mask) {
        for (int col = 0; col < cols; ++col) L[col] = r.mask[col] ? 0.0f : L[col];
    }
    light_bytes(r, L, r.dst);
}

void light_row_portable(const LightRow& r) { light_row_body(r); }

#if defined(__x86_64__) && defined(__GNUC__)
#define OVERFLIGHT_LIGHT_AVX2 1
// The same compiled for AVX2 (8 lanes rather than SSE2's 4; no FMA, so the
// same bits), picked at run time.
__attribute__((target("avx2"))) void light_row_avx2(const LightRow& r) { light_row_body(r); }
#endif

void light_samples(const Terrain& t, const PackedNormals& normals, const Environment& env, const ShadowCeiling* shadow,
                   const std::uint8_t* mask, std::vector<Rgb8>& out, std::vector<Rgb8>* other, LightOutput output) {
    const bool light_only = output == LightOutput::Light;
    out.resize(t.colors().size());
    if (other) other->resize(t.colors().size());
    const glm::vec3 sun = unit_sun(env);
    const bool day = sun.y > 0;
    // N . L with N in steps of 1 / kScale: the packed integers times L / kScale.
    const glm::vec3 l = day ? sun / PackedNormals::kScale : glm::vec3(0.0f);
    const int cols = t.cols();
    const float vs = t.v_scale(), y0 = t.y_offset();
    LightRow r;
    r.cols = cols;
    r.l = l;
    r.vs = vs;
    r.y0 = y0;
    r.light_only = light_only;
    r.amb[0] = env.ambient.r, r.amb[1] = env.ambient.g, r.amb[2] = env.ambient.b;
    r.sun_rgb[0] = env.sun_color.r, r.sun_rgb[1] = env.sun_color.g, r.sun_rgb[2] = env.sun_color.b;
#if OVERFLIGHT_LIGHT_AVX2
    static const bool avx2 = __builtin_cpu_supports("avx2");
#endif
    parallel::for_each_index(0, t.rows(), [&](int row) {
        const std::size_t i0 = t.index(row, 0);
        thread_local std::vector<float> lambert, light;
        lambert.resize(2 * std::size_t(cols)); // the second half: the flipped light (LightRow::other)
        light.resize(3 * std::size_t(cols));
        LightRow q = r;
        q.n = normals.packed.data() + i0;
        q.raw = t.heights().data() + i0;
        q.albedo = reinterpret_cast<const std::uint8_t*>(t.colors().data() + i0);
        q.ceiling = shadow ? shadow->ceiling.data() + i0 : nullptr;
        q.mask = mask ? mask + i0 : nullptr;
        q.L = lambert.data();
        q.LL = light.data();
        q.dst = reinterpret_cast<std::uint8_t*>(out.data() + i0);
        q.other = other && mask ? reinterpret_cast<std::uint8_t*>(other->data() + i0) : nullptr;
#if OVERFLIGHT_LIGHT_AVX2
        if (avx2) {
            light_row_avx2(q);
            return;
        }
#endif
        light_row_portable(q);
    });
}

} // namespace

const std::vector<Rgb8>* TerrainLighting::colors(const Environment& env) {
    if (valid_ && same_light(env, lit_for_)) return baked_ ? nullptr : &colors_;
    valid_ = true;
    lit_for_ = env;
    ++version_;
    baked_ = lighting_is_baked(env);
    masked_ = false;
    if (baked_ && output_ == LightOutput::Light) {
        colors_.assign(terrain_.colors().size(), Rgb8{128, 128, 128});
        baked_ = false; // the light of 1 is what to paint
        return &colors_;
    }
    if (baked_) return nullptr;
    if (normals_.packed.empty()) normals_ = pack_normals(terrain_);
    if (env.shadows) {
        const glm::vec3 sun = unit_sun(env);
        if (!shadow_valid_ || shadow_for_ != sun) {
            if (shared_) {
                shared_shadow_.reset(); // so that the shared sweep may reuse its storage
                shared_shadow_ = shared_->get(sun);
            }
            else sweep_shadow_mask(terrain_, sun, shadow_);
        }
        shadow_valid_ = true;
        shadow_for_ = sun;
        light_colors(terrain_, normals_, env, shared_ ? shared_shadow_->mask : shadow_, colors_, other_colors_,
                     output_);
        masked_ = true;
    } else {
        light_colors(terrain_, normals_, env, nullptr, colors_, output_);
    }
    return &colors_;
}

LightMask TerrainLighting::light_mask() const {
    if (!masked_) return {};
    return {shared_ ? &shared_shadow_->mask : &shadow_, &other_colors_};
}

} // namespace overflight
