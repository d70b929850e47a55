// The web page's terrain file. See WebTerrainFormat.h.
#include "core/WebTerrainFormat.h"

#include "core/BitCast.h"
#include "core/Error.h"

#include <glm/vec3.hpp>

#include <cmath>
#include <cstring>
#include <limits>

namespace overflight {

namespace {

enum Flags : std::uint32_t { kShadows = 1, kBaked = 2, kAtmosphere = 4, kWater = 8, kStartGiven = 16 };

// Little-endian fields, whatever the host's byte order.
class Writer {
public:
    explicit Writer(std::uint8_t* p) : p_(p) {}
    void bytes(const void* b, std::size_t n) {
        std::memcpy(p_, b, n);
        p_ += n;
    }
    void u16(std::uint16_t v) {
        p_[0] = std::uint8_t(v);
        p_[1] = std::uint8_t(v >> 8);
        p_ += 2;
    }
    void u32(std::uint32_t v) {
        for (int i = 0; i < 4; ++i) p_[i] = std::uint8_t(v >> (8 * i));
        p_ += 4;
    }
    void u64(std::uint64_t v) {
        for (int i = 0; i < 8; ++i) p_[i] = std::uint8_t(v >> (8 * i));
        p_ += 8;
    }
    void f32(float v) { u32(bit_cast<std::uint32_t>(v)); }
    void f64(double v) { u64(bit_cast<std::uint64_t>(v)); }
    void vec3(const glm::vec3& v) {
        f32(v.x);
        f32(v.y);
        f32(v.z);
    }

private:
    std::uint8_t* p_;
};

class Reader {
public:
    explicit Reader(const std::uint8_t* p) : p_(p) {}
    std::uint32_t u32() {
        std::uint32_t v = 0;
        for (int i = 0; i < 4; ++i) v |= std::uint32_t(p_[i]) << (8 * i);
        p_ += 4;
        return v;
    }
    std::uint64_t u64() {
        std::uint64_t v = 0;
        for (int i = 0; i < 8; ++i) v |= std::uint64_t(p_[i]) << (8 * i);
        p_ += 8;
        return v;
    }
    float f32() { return bit_cast<float>(u32()); }
    double f64() { return bit_cast<double>(u64()); }
    glm::vec3 vec3() {
        const float x = f32(), y = f32();
        return {x, y, f32()};
    }

private:
    const std::uint8_t* p_;
};

} // namespace

std::uint64_t web_terrain_bytes(int rows, int cols) {
    return kWebTerrainHeaderBytes + std::uint64_t(rows) * std::uint64_t(cols) * (sizeof(std::uint16_t) + 3);
}

std::vector<std::uint8_t> encode_web_terrain(const Terrain& t, const Environment& env, const VehicleStart& start) {
    std::vector<std::uint8_t> out(std::size_t(web_terrain_bytes(t.rows(), t.cols())));
    Writer w(out.data());
    w.bytes(kWebTerrainMagic, sizeof kWebTerrainMagic);
    w.u32(std::uint32_t(t.rows()));
    w.u32(std::uint32_t(t.cols()));
    w.f32(t.h_scale());
    w.f32(t.v_scale());
    w.f32(t.y_offset());
    w.f32(env.sea_level.value_or(std::numeric_limits<float>::quiet_NaN()));
    w.u32((env.shadows ? kShadows : 0u) | (env.baked ? kBaked : 0u) | (env.atmosphere ? kAtmosphere : 0u) |
          (env.water ? kWater : 0u) | (start.given ? kStartGiven : 0u));
    w.vec3(env.sun_dir);
    w.vec3(env.sun_color);
    w.vec3(env.ambient);
    w.f32(env.fog_density);
    w.vec3(env.fog_color);
    w.vec3(env.sky_zenith);
    w.vec3(env.sky_horizon);
    w.f32(env.water_level);
    w.vec3(env.air.rayleigh);
    w.f32(env.air.haze);
    w.f32(env.air.scale_height);
    w.f32(env.air.haze_g);
    w.f32(env.air.exposure);
    w.vec3(env.air.sunlight);
    w.f64(start.x);
    w.f64(start.z);
    w.f64(start.heading);
    for (const std::uint16_t h : t.heights()) w.u16(h);
    for (const Rgb8 c : t.colors()) {
        const std::uint8_t rgb[3] = {c.r, c.g, c.b};
        w.bytes(rgb, 3);
    }
    return out;
}

bool is_web_terrain(std::span<const std::uint8_t> bytes) {
    return bytes.size() >= sizeof kWebTerrainMagic &&
           std::memcmp(bytes.data(), kWebTerrainMagic, sizeof kWebTerrainMagic) == 0;
}

WebTerrain decode_web_terrain(std::span<const std::uint8_t> bytes, const std::string& name) {
    if (!is_web_terrain(bytes)) throw Error(name, "is not an Overflight web terrain (no OFTERR01 magic)");
    if (bytes.size() < kWebTerrainHeaderBytes)
        throw Error(name, "is truncated: " + std::to_string(bytes.size()) + " bytes, less than its header's " +
                              std::to_string(kWebTerrainHeaderBytes));
    Reader r(bytes.data() + sizeof kWebTerrainMagic);
    const auto rows = std::int32_t(r.u32()), cols = std::int32_t(r.u32());
    if (rows < 2 || cols < 2 || rows > 65537 || cols > 65537)
        throw Error(name, "size " + std::to_string(rows) + "x" + std::to_string(cols) +
                              " is outside 2..65537 samples per side");
    const std::uint64_t expected = web_terrain_bytes(rows, cols);
    if (bytes.size() != expected)
        throw Error(name, "has " + std::to_string(bytes.size()) + " bytes, " + std::to_string(expected) + " expected for " +
                              std::to_string(rows) + "x" + std::to_string(cols) + " samples");
    const float h_scale = r.f32(), v_scale = r.f32(), y_offset = r.f32(), sea_level = r.f32();
    if (const std::string problem = horizontal_scale_problem(rows, cols, h_scale); !problem.empty())
        throw Error(name, problem);
    if (!std::isfinite(v_scale) || !std::isfinite(y_offset))
        throw Error(name, "vertical scale and offset must be finite numbers");

    WebTerrain out{Terrain(rows, cols, h_scale, v_scale, y_offset), {}, {}};
    Environment& env = out.environment;
    const std::uint32_t flags = r.u32();
    env.shadows = flags & kShadows;
    env.baked = flags & kBaked;
    env.atmosphere = flags & kAtmosphere;
    env.water = flags & kWater;
    if (!std::isnan(sea_level)) env.sea_level = sea_level;
    env.sun_dir = r.vec3();
    env.sun_color = r.vec3();
    env.ambient = r.vec3();
    env.fog_density = r.f32();
    env.fog_color = r.vec3();
    env.sky_zenith = r.vec3();
    env.sky_horizon = r.vec3();
    env.water_level = r.f32();
    env.air.rayleigh = r.vec3();
    env.air.haze = r.f32();
    env.air.scale_height = r.f32();
    env.air.haze_g = r.f32();
    env.air.exposure = r.f32();
    env.air.sunlight = r.vec3();
    out.start.given = flags & kStartGiven;
    out.start.x = r.f64();
    out.start.z = r.f64();
    out.start.heading = r.f64();

    const float fields[] = {env.sun_dir.x, env.sun_dir.y, env.sun_dir.z, env.sun_color.x, env.sun_color.y,
                            env.sun_color.z, env.ambient.x, env.ambient.y, env.ambient.z, env.fog_density,
                            env.fog_color.x, env.fog_color.y, env.fog_color.z, env.sky_zenith.x, env.sky_zenith.y,
                            env.sky_zenith.z, env.sky_horizon.x, env.sky_horizon.y, env.sky_horizon.z,
                            env.water_level, env.air.rayleigh.x, env.air.rayleigh.y, env.air.rayleigh.z,
                            env.air.haze, env.air.scale_height, env.air.haze_g, env.air.exposure,
                            env.air.sunlight.x, env.air.sunlight.y, env.air.sunlight.z};
    for (const float f : fields)
        if (!std::isfinite(f)) throw Error(name, "has an environment value that is not a finite number");
    if (env.sea_level && !std::isfinite(*env.sea_level)) throw Error(name, "sea level is not a finite number");
    if (!std::isfinite(out.start.x) || !std::isfinite(out.start.z) || !std::isfinite(out.start.heading))
        throw Error(name, "vehicle start is not a finite position and heading");

    const std::uint8_t* p = bytes.data() + kWebTerrainHeaderBytes;
    for (std::uint16_t& h : out.terrain.heights()) {
        h = std::uint16_t(p[0] | (p[1] << 8));
        p += 2;
    }
    for (Rgb8& c : out.terrain.colors()) {
        c = {p[0], p[1], p[2]};
        p += 3;
    }
    return out;
}

} // namespace overflight
