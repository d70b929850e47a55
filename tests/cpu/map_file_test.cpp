// The hovercraft `map` file in TOML (CMSC 23700 project 2a, sec. 6.1; DESIGN sec. 4, 5):
// values, defaults, a round trip, and one test per bad input.
#include "TestSupport.h"
#include "core/Error.h"
#include "io/MapFile.h"

namespace overflight {
namespace {

std::string problem_of(const std::string& text) {
    try {
        parse_map(text, "data/map");
    } catch (const Error& e) {
        EXPECT_EQ(e.subject(), "data/map");
        EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos) << "error must be one line";
        return e.problem();
    }
    ADD_FAILURE() << "no Error for:\n" << text;
    return {};
}

TEST(MapFile, ParsesEveryKey) {
    const MapFile m = parse_map(R"(
h_scale = 10
v_scale = 0.1
sun_dir = [0.0, 1.0, 0.0]
sun_color = [1.0, 0.5, 0.25]
fog_density = 0.002
fog_color = [0.5, 0.6, 0.7]

[vehicle]
x = 100.0
z = 200
heading = 90.0

[[object]]
kind = "house"
x = 50.0
z = 60.0
heading = 45.0

[[line]]
points = [[0.0, 0.0], [100.0, 0.0], [200.0, 50.0]]
height = 30.0
)", "map", "/data/set");
    EXPECT_DOUBLE_EQ(m.h_scale, 10.0);
    EXPECT_DOUBLE_EQ(m.v_scale, 0.1);
    EXPECT_DOUBLE_EQ(m.y_offset, 0.0);
    EXPECT_EQ(m.environment.sun_dir, glm::vec3(0, 1, 0));
    EXPECT_EQ(m.environment.sun_color, glm::vec3(1.0f, 0.5f, 0.25f));
    EXPECT_FLOAT_EQ(m.environment.fog_density, 0.002f);
    EXPECT_EQ(m.environment.fog_color, glm::vec3(0.5f, 0.6f, 0.7f));
    EXPECT_TRUE(m.start.given);
    EXPECT_DOUBLE_EQ(m.start.x, 100.0);
    EXPECT_DOUBLE_EQ(m.start.z, 200.0);
    EXPECT_DOUBLE_EQ(m.start.heading, 90.0);
    ASSERT_EQ(m.scene.objects.size(), 1u);
    EXPECT_EQ(m.scene.objects[0].kind, ObjectKind::House);
    EXPECT_DOUBLE_EQ(m.scene.objects[0].heading, 45.0);
    ASSERT_EQ(m.scene.lines.size(), 1u);
    EXPECT_EQ(m.scene.lines[0].points.size(), 3u);
    EXPECT_DOUBLE_EQ(m.scene.lines[0].points[2].y, 50.0);
    EXPECT_DOUBLE_EQ(m.scene.lines[0].height, 30.0);
    EXPECT_DOUBLE_EQ(m.scene.lines[0].sag, 4.0); // default
}

TEST(MapFile, OnlyScalesAreRequired) {
    const MapFile m = parse_map("h_scale = 2.5\nv_scale = 0.25\n", "map");
    const Environment defaults;
    EXPECT_EQ(m.environment.sun_dir, defaults.sun_dir);
    EXPECT_EQ(m.environment.fog_density, defaults.fog_density);
    EXPECT_FALSE(m.start.given);
    EXPECT_TRUE(m.scene.empty());
}

TEST(MapFile, FormatRoundTrips) {
    MapFile m;
    m.h_scale = 30.0;
    m.v_scale = 0.05f; // a float value, as Terrain stores it
    m.y_offset = -60.0;
    m.environment.fog_density = 0.0003f;
    m.start = VehicleStart{true, 12.5, 40.0, 270.0};
    SceneObject box;
    box.kind = ObjectKind::Box;
    box.x = 1;
    box.z = 2;
    box.y = 3;
    box.color = Rgb8{200, 40, 40};
    m.scene.objects.push_back(box);
    m.scene.lines.push_back(TransmissionLine{{{0, 0}, {10, 20}}, 35, 2, Rgb8{1, 2, 3}});
    const MapFile back = parse_map(format_map(m), "map");
    EXPECT_EQ(float(back.v_scale), 0.05f);
    EXPECT_DOUBLE_EQ(back.h_scale, 30.0);
    EXPECT_DOUBLE_EQ(back.y_offset, -60.0);
    EXPECT_EQ(back.environment.fog_density, 0.0003f);
    EXPECT_EQ(back.start.heading, 270.0);
    ASSERT_EQ(back.scene.objects.size(), 1u);
    EXPECT_EQ(back.scene.objects[0].y, std::optional<double>(3.0));
    EXPECT_EQ(back.scene.objects[0].color, (Rgb8{200, 40, 40}));
    ASSERT_EQ(back.scene.lines.size(), 1u);
    EXPECT_EQ(back.scene.lines[0].points[1], glm::dvec2(10, 20));
    EXPECT_EQ(back.scene.lines[0].color, (Rgb8{1, 2, 3}));
}

TEST(MapFile, SyntaxErrorNamesTheLine) {
    const std::string p = problem_of("h_scale = 1\nv_scale = 1\nsun_dir = [1, 2\n");
    EXPECT_EQ(p.rfind("line 3", 0), 0u) << p;
}

TEST(MapFile, MissingHScale) {
    EXPECT_NE(problem_of("v_scale = 1\n").find("missing key h_scale"), std::string::npos);
}

TEST(MapFile, MissingVScale) {
    EXPECT_NE(problem_of("h_scale = 1\n").find("missing key v_scale"), std::string::npos);
}

TEST(MapFile, WrongTypedKeyNamesKeyAndLine) {
    const std::string p = problem_of("h_scale = 1\n\nv_scale = \"tall\"\n");
    EXPECT_NE(p.find("line 3"), std::string::npos) << p;
    EXPECT_NE(p.find("v_scale must be a number"), std::string::npos) << p;
}

TEST(MapFile, WrongTypedVector) {
    EXPECT_NE(problem_of("h_scale = 1\nv_scale = 1\nsun_dir = [1, 2]\n").find("sun_dir"), std::string::npos);
    EXPECT_NE(problem_of("h_scale = 1\nv_scale = 1\nfog_color = \"grey\"\n").find("fog_color"), std::string::npos);
}

TEST(MapFile, NonPositiveScale) {
    EXPECT_NE(problem_of("h_scale = 0\nv_scale = 1\n").find("h_scale must be positive"), std::string::npos);
    EXPECT_NE(problem_of("h_scale = 1\nv_scale = -2\n").find("v_scale must be positive"), std::string::npos);
}

TEST(MapFile, UnknownKey) {
    EXPECT_NE(problem_of("h_scale = 1\nv_scale = 1\nfog_densty = 0.1\n").find("unknown key 'fog_densty'"),
              std::string::npos);
}

TEST(MapFile, VehicleNeedsPosition) {
    EXPECT_NE(problem_of("h_scale = 1\nv_scale = 1\n[vehicle]\nheading = 3\n").find("missing key x"),
              std::string::npos);
    EXPECT_NE(problem_of("h_scale = 1\nv_scale = 1\nvehicle = 3\n").find("vehicle must be a table"),
              std::string::npos);
}

TEST(MapFile, BadObjectInMap) {
    EXPECT_NE(problem_of("h_scale = 1\nv_scale = 1\n[[object]]\nkind = \"castle\"\nx = 1\nz = 1\n").find("castle"),
              std::string::npos);
}

// Found by fuzz_map: a double beyond float range became inf in the float
// fields and the formatted map no longer parsed.
TEST(MapFile, BeyondFloatRange) {
    EXPECT_NE(problem_of("h_scale = 1\nv_scale = 1\nfog_density = 1e300\n").find("fog_density is beyond float range"),
              std::string::npos);
    EXPECT_NE(problem_of("h_scale = 1\nv_scale = 1\nsun_dir = [1e39, 0, 1]\n").find("sun_dir must be"), std::string::npos);
}

TEST(MapFile, MissingFile) {
    test::ScratchDir dir;
    try {
        load_map(dir / "map");
        FAIL();
    } catch (const Error& e) {
        EXPECT_EQ(e.subject(), dir / "map");
    }
}

} // namespace
} // namespace overflight

namespace overflight {

TEST(MapFile, SeaLevelIsOptionalAndRoundTrips) {
    EXPECT_FALSE(parse_map("h_scale = 1.0\nv_scale = 1.0\n", "map").environment.sea_level);
    const MapFile m = parse_map("h_scale = 1.0\nv_scale = 1.0\nsea_level = -3.5\n", "map");
    ASSERT_TRUE(m.environment.sea_level);
    EXPECT_EQ(*m.environment.sea_level, -3.5f);
    EXPECT_EQ(parse_map(format_map(m), "map").environment.sea_level, -3.5f);
    EXPECT_THROW(parse_map("h_scale = 1.0\nv_scale = 1.0\nsea_level = \"low\"\n", "map"), Error);
}

} // namespace overflight
