// CPU-side checks: catenary geometry of transmission-line cables (DESIGN sec. 5)
// and the OBJ/glTF model loader's results and one-line errors.
#include "TestSupport.h"
#include "core/Error.h"
#include "gl/Catenary.h"
#include "io/ModelLoader.h"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>

using namespace overflight;

TEST(Catenary, ParameterSolvesTheSagEquation) {
    // Span 100, sag 4: the parabola estimate a = L^2 / (8 sag) = 312.5; the
    // catenary's a is slightly larger (cosh x - 1 > x^2 / 2, so the same a would sag more).
    const double a = gl::catenary_parameter(100, 4);
    EXPECT_NEAR(a * (std::cosh(50 / a) - 1), 4.0, 1e-9);
    EXPECT_GT(a, 312.5);
    EXPECT_LT(a, 315.0);
    EXPECT_THROW(gl::catenary_parameter(100, 0), Error);
}

TEST(Catenary, CableHangsSagBelowTheChordAtMidSpan) {
    const glm::dvec3 A(0, 40, 0), B(100, 40, 0);
    const auto p = gl::catenary_points(A, B, 4.0, 4);
    ASSERT_EQ(p.size(), 5u);
    EXPECT_EQ(p.front(), A);
    EXPECT_EQ(p.back(), B);
    EXPECT_NEAR(p[2].y, 36.0, 1e-9);               // mid-span: 40 - sag
    EXPECT_NEAR(p[2].x, 50.0, 1e-12);
    EXPECT_NEAR(p[1].y, p[3].y, 1e-9);             // symmetric
    // Quarter span: parabola gives 3/4 sag = 3.0; the catenary is within 0.01 of it.
    EXPECT_NEAR(40.0 - p[1].y, 3.0, 0.01);
    EXPECT_NEAR(gl::catenary_drop(100, 4, 25), 40.0 - p[1].y, 1e-9);
    // Inclined span: the sag is measured from the chord.
    const auto q = gl::catenary_points({0, 10, 0}, {0, 30, 200}, 6.0, 2);
    EXPECT_NEAR(q[1].y, 20.0 - 6.0, 1e-9);
    // No sag: the straight chord.
    EXPECT_NEAR(gl::catenary_points(A, B, 0.0, 2)[1].y, 40.0, 1e-12);
}

namespace {
void write(const std::string& path, const std::string& text) { std::ofstream(path) << text; }
} // namespace

TEST(ModelLoader, ReadsObjWithMaterialColor) {
    test::ScratchDir dir;
    write(dir / "m.mtl", "newmtl red\nKd 1 0 0\n");
    write(dir / "m.obj", "mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nusemtl red\nf 1 2 3 4\n");
    const MeshArrays m = load_model(dir / "m.obj");
    ASSERT_EQ(m.triangle_count(), 2u); // the quad is triangulated
    EXPECT_EQ(m.colors[0], (Rgb8{255, 0, 0}));
    EXPECT_NEAR(m.normals[0].z, 1.0f, 1e-6); // counter-clockwise in XY faces +Z
}

TEST(ModelLoader, ReadsGltfWithEmbeddedBuffer) {
    test::ScratchDir dir;
    // One triangle (0,0,0) (1,0,0) (0,0,-1) as float32 little endian, base64 in a data URI.
    write(dir / "t.gltf", R"({"asset":{"version":"2.0"},"scene":0,"scenes":[{"nodes":[0]}],
      "nodes":[{"mesh":0,"translation":[0,2,0]}],
      "meshes":[{"primitives":[{"attributes":{"POSITION":0},"material":0}]}],
      "materials":[{"pbrMetallicRoughness":{"baseColorFactor":[0,1,0,1]}}],
      "buffers":[{"byteLength":36,"uri":"data:application/octet-stream;base64,AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAAAAAAIC/"}],
      "bufferViews":[{"buffer":0,"byteLength":36}],
      "accessors":[{"bufferView":0,"componentType":5126,"count":3,"type":"VEC3","min":[0,0,-1],"max":[1,0,0]}]})");
    const MeshArrays m = load_model(dir / "t.gltf");
    ASSERT_EQ(m.triangle_count(), 1u);
    EXPECT_NEAR(m.positions[1].x, 1.0f, 1e-6);
    EXPECT_NEAR(m.positions[1].y, 2.0f, 1e-6); // node translation applied
    EXPECT_NEAR(m.normals[0].y, 1.0f, 1e-6);
    EXPECT_EQ(m.colors[0], (Rgb8{0, 255, 0}));
}

TEST(ModelLoader, BadFilesGiveOneLineErrorsNamingTheFile) {
    test::ScratchDir dir;
    write(dir / "bad.obj", "v 0 0 0\nv 1 0 0\nf 1 2 7\n");
    write(dir / "empty.obj", "# nothing\n");
    write(dir / "bad.gltf", "{ not json");
    write(dir / "x.stl", "solid");
    for (const std::string name : {"missing.obj", "bad.obj", "empty.obj", "bad.gltf", "x.stl"}) {
        try {
            load_model(dir / name);
            ADD_FAILURE() << name << " loaded";
        } catch (const Error& e) {
            EXPECT_EQ(e.subject(), dir / name);
            EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos) << e.what();
            std::printf("%s\n", e.what());
        }
    }
}
