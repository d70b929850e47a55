// Scene files (DESIGN sec. 5): every kind, model paths relative to the scene
// file, and one test per bad input.
#include "TestSupport.h"
#include "core/Error.h"
#include "io/SceneFile.h"

#include <fstream>

namespace overflight {
namespace {

std::string problem_of(const std::string& text) {
    try {
        parse_scene(text, "scene.toml");
    } catch (const Error& e) {
        EXPECT_EQ(e.subject(), "scene.toml");
        return e.problem();
    }
    ADD_FAILURE() << "no Error for:\n" << text;
    return {};
}

TEST(SceneFile, ParsesTheDesignExample) {
    const Scene s = parse_scene(R"(
[[object]]
kind = "box"
x = 4890.0
z = 13800.0
width = 60.0
height = 120.0
depth = 60.0
heading = 0.0
color = [200, 40, 40]

[[object]]
kind = "tower"
x = 1
y = 7.5
z = 2

[[line]]
points = [[1000.0, 2000.0], [1400.0, 2100.0], [1800.0, 2300.0]]
height = 40.0
sag = 4.0
)", "scene.toml");
    ASSERT_EQ(s.objects.size(), 2u);
    const SceneObject& box = s.objects[0];
    EXPECT_EQ(box.kind, ObjectKind::Box);
    EXPECT_DOUBLE_EQ(box.x, 4890.0);
    EXPECT_DOUBLE_EQ(box.z, 13800.0);
    EXPECT_FALSE(box.y.has_value()); // terrain height, decided by the renderer
    EXPECT_DOUBLE_EQ(box.width, 60.0);
    EXPECT_DOUBLE_EQ(box.height, 120.0);
    EXPECT_EQ(box.color, (Rgb8{200, 40, 40}));
    EXPECT_EQ(s.objects[1].kind, ObjectKind::Tower);
    EXPECT_EQ(s.objects[1].y, std::optional<double>(7.5));
    ASSERT_EQ(s.lines.size(), 1u);
    EXPECT_EQ(s.lines[0].points[1], glm::dvec2(1400.0, 2100.0));
    EXPECT_DOUBLE_EQ(s.lines[0].sag, 4.0);
}

TEST(SceneFile, ModelPathIsRelativeToTheSceneFileAndTheModelIsLoadedWithIt) {
    test::ScratchDir dir;
    std::filesystem::create_directories(dir.path / "scenes/models");
    std::ofstream(dir / "scenes/models/tree.obj") << "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 2 3\nf 1 3 4\n";
    const std::string path = dir / "scenes/town.toml";
    std::ofstream(path) << "[[object]]\nkind = \"model\"\nx = 1\nz = 2\nscale = 2.5\nfile = \"models/tree.obj\"\n"
                           "[[object]]\nkind = \"vehicle\"\nx = 3\nz = 4\n";
    const Scene s = load_scene(path);
    ASSERT_EQ(s.objects.size(), 2u);
    EXPECT_EQ(s.objects[0].kind, ObjectKind::Model);
    EXPECT_EQ(s.objects[0].model_path, (dir.path / "scenes/models/tree.obj").string());
    EXPECT_DOUBLE_EQ(s.objects[0].scale, 2.5);
    ASSERT_TRUE(s.objects[0].model);
    EXPECT_EQ(s.objects[0].model->triangle_count(), 2u);
    EXPECT_EQ(s.objects[1].kind, ObjectKind::Vehicle);
    EXPECT_FALSE(s.objects[1].model);
}

TEST(SceneFile, AMissingModelFailsWhenTheSceneIsRead) {
    test::ScratchDir dir;
    const std::string path = dir / "town.toml";
    std::ofstream(path) << "[[object]]\nkind = \"model\"\nx = 1\nz = 2\nfile = \"nowhere.obj\"\n";
    try {
        load_scene(path);
        FAIL() << "a scene with a missing model loaded";
    } catch (const Error& e) {
        EXPECT_EQ(e.subject(), dir / "nowhere.obj");
    }
}

TEST(SceneFile, EmptyFileIsAnEmptyScene) { EXPECT_TRUE(parse_scene("", "scene.toml").empty()); }

TEST(SceneFile, UnknownKind) {
    const std::string p = problem_of("[[object]]\nkind = \"castle\"\nx = 1\nz = 1\n");
    EXPECT_NE(p.find("line 2"), std::string::npos) << p;
    EXPECT_NE(p.find("unknown object kind 'castle'"), std::string::npos) << p;
}

TEST(SceneFile, MissingKind) { EXPECT_NE(problem_of("[[object]]\nx = 1\nz = 1\n").find("kind"), std::string::npos); }

TEST(SceneFile, MissingPosition) {
    EXPECT_NE(problem_of("[[object]]\nkind = \"box\"\nx = 1\n").find("missing key z"), std::string::npos);
}

TEST(SceneFile, WrongTypedNumber) {
    const std::string p = problem_of("[[object]]\nkind = \"box\"\nx = 1\nz = 1\nwidth = \"wide\"\n");
    EXPECT_NE(p.find("line 5: width must be a number"), std::string::npos) << p;
}

TEST(SceneFile, WrongTypedColor) {
    EXPECT_NE(problem_of("[[object]]\nkind = \"box\"\nx = 1\nz = 1\ncolor = [300, 0, 0]\n").find("color"),
              std::string::npos);
    EXPECT_NE(problem_of("[[object]]\nkind = \"box\"\nx = 1\nz = 1\ncolor = \"red\"\n").find("color"),
              std::string::npos);
}

TEST(SceneFile, FloatColorBeyondIntegerRange) {
    // toml++ converts a float to int64 without a range check (undefined for
    // 3e40): a color must be checked to be an integer before it is read as one.
    for (const char* value : {"3E40", "3e40", "-3e40", "255.0", "nan"}) {
        const std::string p =
            problem_of("[[object]]\nkind = \"box\"\nx = 1\nz = 1\ncolor = [" + std::string(value) + ", 0, 0]\n");
        EXPECT_EQ(p, "line 5: color must be [r, g, b] with integers 0..255") << value;
        EXPECT_NE(problem_of("[[line]]\npoints = [[0, 0], [1, 1]]\ncolor = [0, " + std::string(value) + ", 0]\n")
                      .find("color must be [r, g, b] with integers 0..255"),
                  std::string::npos)
            << value;
    }
    EXPECT_EQ(parse_scene("[[object]]\nkind = \"box\"\nx = 1\nz = 1\ncolor = [255, 0, 7]\n", "s").objects[0].color,
              (Rgb8{255, 0, 7}));
}

TEST(SceneFile, ModelWithoutFile) {
    EXPECT_NE(problem_of("[[object]]\nkind = \"model\"\nx = 1\nz = 1\n").find("without file"), std::string::npos);
}

TEST(SceneFile, NegativeSize) {
    EXPECT_NE(problem_of("[[object]]\nkind = \"box\"\nx = 1\nz = 1\nheight = -3\n").find("positive"),
              std::string::npos);
}

TEST(SceneFile, LineWithOnePoint) {
    EXPECT_NE(problem_of("[[line]]\npoints = [[1.0, 2.0]]\n").find("at least two"), std::string::npos);
}

TEST(SceneFile, LineWithBadPoint) {
    EXPECT_NE(problem_of("[[line]]\npoints = [[1.0, 2.0], [3.0]]\n").find("[x, z]"), std::string::npos);
}

TEST(SceneFile, ObjectNotAnArrayOfTables) {
    EXPECT_NE(problem_of("object = 3\n").find("[[object]]"), std::string::npos);
}

TEST(SceneFile, UnknownTopLevelKey) {
    EXPECT_NE(problem_of("houses = 3\n").find("unknown key 'houses'"), std::string::npos);
}

TEST(SceneFile, SyntaxError) { EXPECT_EQ(problem_of("[[object]\n").rfind("line 1", 0), 0u); }

TEST(SceneFile, MissingFileNamesThePath) {
    test::ScratchDir dir;
    try {
        load_scene(dir / "none.toml");
        FAIL();
    } catch (const Error& e) {
        EXPECT_EQ(e.subject(), dir / "none.toml");
        EXPECT_NE(e.problem().find("no such file"), std::string::npos);
    }
}

} // namespace
} // namespace overflight
