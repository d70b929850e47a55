// The web page's terrain file (core/WebTerrainFormat.h): every field round-
// trips bit for bit, the layout is the documented one on a hand-made file, and
// every way a file can be broken is one Error naming it.
#include "core/DemoIsland.h"
#include "core/Error.h"
#include "core/WebTerrainFormat.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>

using namespace overflight;

namespace {

// Every environment field set to a value unlike its default.
Environment odd_environment() {
    Environment e;
    e.sun_dir = {-0.25f, 0.5f, 0.75f};
    e.sun_color = {0.9f, 0.8f, 0.7f};
    e.ambient = {0.1f, 0.2f, 0.3f};
    e.shadows = true;
    e.baked = true;
    e.fog_density = 1.5e-4f;
    e.fog_color = {0.4f, 0.5f, 0.6f};
    e.sky_zenith = {0.11f, 0.22f, 0.33f};
    e.sky_horizon = {0.44f, 0.55f, 0.66f};
    e.atmosphere = true;
    e.air.rayleigh = {1e-6f, 2e-6f, 3e-6f};
    e.air.haze = 4e-5f;
    e.air.scale_height = 1234.5f;
    e.air.haze_g = 0.6f;
    e.air.exposure = 1.5f;
    e.air.sunlight = {0.95f, 0.9f, 0.85f};
    e.water = true;
    e.water_level = 12.25f;
    e.sea_level = 3.5f;
    return e;
}

void expect_same(const Environment& a, const Environment& b) {
    EXPECT_EQ(a.sun_dir, b.sun_dir);
    EXPECT_EQ(a.sun_color, b.sun_color);
    EXPECT_EQ(a.ambient, b.ambient);
    EXPECT_EQ(a.shadows, b.shadows);
    EXPECT_EQ(a.baked, b.baked);
    EXPECT_EQ(a.fog_density, b.fog_density);
    EXPECT_EQ(a.fog_color, b.fog_color);
    EXPECT_EQ(a.sky_zenith, b.sky_zenith);
    EXPECT_EQ(a.sky_horizon, b.sky_horizon);
    EXPECT_EQ(a.atmosphere, b.atmosphere);
    EXPECT_EQ(a.air.rayleigh, b.air.rayleigh);
    EXPECT_EQ(a.air.haze, b.air.haze);
    EXPECT_EQ(a.air.scale_height, b.air.scale_height);
    EXPECT_EQ(a.air.haze_g, b.air.haze_g);
    EXPECT_EQ(a.air.exposure, b.air.exposure);
    EXPECT_EQ(a.air.sunlight, b.air.sunlight);
    EXPECT_EQ(a.water, b.water);
    EXPECT_EQ(a.water_level, b.water_level);
    EXPECT_EQ(a.sea_level, b.sea_level);
}

std::vector<std::uint8_t> small_file() {
    Terrain t(2, 3, 2.5f, 0.5f, -10.0f);
    t.heights() = {1, 2, 3, 0x1234, 65535, 0};
    t.colors() = {{1, 2, 3}, {4, 5, 6}, {7, 8, 9}, {10, 11, 12}, {13, 14, 15}, {16, 17, 18}};
    return encode_web_terrain(t, Environment{}, VehicleStart{});
}

void expect_error(const std::vector<std::uint8_t>& bytes, const std::string& fragment) {
    try {
        decode_web_terrain(bytes, "site/terrain.bin");
        FAIL() << "accepted a broken file (" << fragment << ")";
    } catch (const Error& e) {
        EXPECT_EQ(e.subject(), "site/terrain.bin");
        EXPECT_NE(e.problem().find(fragment), std::string::npos) << e.what();
        EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos);
    }
}

} // namespace

TEST(WebTerrainFormat, DemoRoundTripsBitForBit) {
    DataSet d = make_demo_island({.size = 129});
    d.environment = odd_environment();
    d.start = {true, 321.5, 654.25, 123.0};
    const std::vector<std::uint8_t> bytes = encode_web_terrain(d.terrain, d.environment, d.start);
    ASSERT_EQ(bytes.size(), web_terrain_bytes(129, 129));
    EXPECT_TRUE(is_web_terrain(bytes));
    const WebTerrain w = decode_web_terrain(bytes);
    EXPECT_EQ(w.terrain.rows(), 129);
    EXPECT_EQ(w.terrain.cols(), 129);
    EXPECT_EQ(w.terrain.h_scale(), d.terrain.h_scale());
    EXPECT_EQ(w.terrain.v_scale(), d.terrain.v_scale());
    EXPECT_EQ(w.terrain.y_offset(), d.terrain.y_offset());
    EXPECT_EQ(w.terrain.heights(), d.terrain.heights());
    EXPECT_EQ(w.terrain.colors(), d.terrain.colors());
    expect_same(w.environment, d.environment);
    EXPECT_TRUE(w.start.given);
    EXPECT_EQ(w.start.x, 321.5);
    EXPECT_EQ(w.start.z, 654.25);
    EXPECT_EQ(w.start.heading, 123.0);
    // Decoded and encoded again: the same bytes.
    EXPECT_EQ(encode_web_terrain(w.terrain, w.environment, w.start), bytes);
}

TEST(WebTerrainFormat, DefaultsRoundTripWithoutSeaLevelOrStart) {
    const std::vector<std::uint8_t> bytes = small_file();
    const WebTerrain w = decode_web_terrain(bytes);
    expect_same(w.environment, Environment{});
    EXPECT_FALSE(w.environment.sea_level.has_value());
    EXPECT_FALSE(w.start.given);
}

TEST(WebTerrainFormat, LayoutByHand) {
    const std::vector<std::uint8_t> b = small_file();
    ASSERT_EQ(b.size(), kWebTerrainHeaderBytes + 6 * 2 + 6 * 3);
    EXPECT_EQ(std::memcmp(b.data(), "OFTERR01", 8), 0);
    EXPECT_EQ(b[8], 2); // rows, little-endian int32
    EXPECT_EQ(b[9] | b[10] | b[11], 0);
    EXPECT_EQ(b[12], 3); // cols
    float h_scale = 0, sea = 0, sun_x = 0;
    std::memcpy(&h_scale, &b[16], 4); // a little-endian host reads the fields in place
    std::memcpy(&sea, &b[28], 4);
    std::memcpy(&sun_x, &b[36], 4);
    EXPECT_EQ(h_scale, 2.5f);
    EXPECT_TRUE(std::isnan(sea));
    EXPECT_EQ(sun_x, Environment{}.sun_dir.x);
    const std::size_t h = kWebTerrainHeaderBytes;
    EXPECT_EQ(b[h + 6], 0x34); // heights[3] = 0x1234, low byte first
    EXPECT_EQ(b[h + 7], 0x12);
    EXPECT_EQ(b[h + 12], 1); // colors[0]
    EXPECT_EQ(b[h + 12 + 17], 18); // colors[5].b
}

TEST(WebTerrainFormat, BrokenFilesAreOneLineErrors) {
    const std::vector<std::uint8_t> good = small_file();
    expect_error({}, "OFTERR01");
    std::vector<std::uint8_t> b = good;
    b[7] = '2';
    expect_error(b, "OFTERR01");
    expect_error(std::vector<std::uint8_t>(good.begin(), good.begin() + 100), "truncated");
    expect_error(std::vector<std::uint8_t>(good.begin(), good.end() - 1), "bytes");
    b = good;
    b.push_back(0);
    expect_error(b, "bytes");
    b = good;
    b[8] = 1; // 1 row
    expect_error(b, "outside 2..65537");
    b = good;
    b[11] = 0x80; // negative rows
    expect_error(b, "outside 2..65537");
    b = good;
    b[12] = 0xff, b[13] = 0xff, b[14] = 0xff, b[15] = 0x7f; // 2^31-1 cols: no such file can be this short
    expect_error(b, "outside 2..65537");
    b = good;
    b[12] = 0x01, b[13] = 0x00, b[14] = 0x01; // 65537 cols: size checked before anything is allocated
    expect_error(b, "bytes");
    const float nan = std::numeric_limits<float>::quiet_NaN(), inf = std::numeric_limits<float>::infinity();
    b = good;
    std::memcpy(&b[16], &nan, 4);
    expect_error(b, "horizontal scale");
    b = good;
    std::memcpy(&b[20], &inf, 4);
    expect_error(b, "vertical scale");
    b = good;
    std::memcpy(&b[28], &inf, 4);
    expect_error(b, "sea level");
    b = good;
    std::memcpy(&b[72], &nan, 4); // fog density
    expect_error(b, "environment");
    b = good;
    const double dnan = std::numeric_limits<double>::quiet_NaN();
    std::memcpy(&b[156], &dnan, 8);
    expect_error(b, "vehicle start");
}
