// PGM/PPM parsing and writing (CMSC 23700 project 2a, sec. 6.2-6.3): literals worked out by
// hand from the Netpbm layout, round trips, and each malformed input.
#include "TestSupport.h"
#include "core/Error.h"
#include "io/Pnm.h"

#include <fstream>
#include <string>

namespace overflight {
namespace {

using test::ScratchDir;

std::vector<std::uint8_t> bytes(const std::string& header, std::initializer_list<int> body = {}) {
    std::vector<std::uint8_t> b(header.begin(), header.end());
    for (int v : body) b.push_back(std::uint8_t(v));
    return b;
}

GrayImage16 pgm(const std::vector<std::uint8_t>& b) { return parse_pgm(b.data(), b.size(), "hf.pgm"); }

// The problem text of the Error thrown by f, with its subject checked.
template <typename F>
std::string problem_of(F&& f, const std::string& subject = "hf.pgm") {
    try {
        f();
    } catch (const Error& e) {
        EXPECT_EQ(e.subject(), subject);
        return e.problem();
    }
    ADD_FAILURE() << "no Error thrown";
    return {};
}

TEST(Pnm, Parses8BitPgmWithComments) {
    const GrayImage16 g = pgm(bytes("P5\n# made by hand\n3 2\n# another\n255\n", {0, 1, 2, 253, 254, 255}));
    EXPECT_EQ(g.maxval, 255);
    ASSERT_EQ(g.image.width, 3);
    ASSERT_EQ(g.image.height, 2);
    EXPECT_EQ(g.image.at(0, 0), 0);
    EXPECT_EQ(g.image.at(2, 0), 2);
    EXPECT_EQ(g.image.at(0, 1), 253);
    EXPECT_EQ(g.image.at(2, 1), 255);
}

TEST(Pnm, Parses16BitPgmBigEndian) {
    // 0x0102 = 258, 0xFFFF = 65535, 0x8000 = 32768, 0x00FF = 255.
    const GrayImage16 g = pgm(bytes("P5 2 2 65535\n", {0x01, 0x02, 0xFF, 0xFF, 0x80, 0x00, 0x00, 0xFF}));
    EXPECT_EQ(g.maxval, 65535);
    EXPECT_EQ(g.image.at(0, 0), 258);
    EXPECT_EQ(g.image.at(1, 0), 65535);
    EXPECT_EQ(g.image.at(0, 1), 32768);
    EXPECT_EQ(g.image.at(1, 1), 255);
}

TEST(Pnm, MaxvalAbove255MeansTwoBytes) {
    // maxval 256 already needs two bytes per sample: 0x0100 = 256.
    const GrayImage16 g = pgm(bytes("P5\n1 1\n256\n", {0x01, 0x00}));
    EXPECT_EQ(g.image.at(0, 0), 256);
}

TEST(Pnm, Pgm16RoundTrip) {
    ScratchDir dir;
    Image2D<std::uint16_t> img(3, 3);
    const std::uint16_t values[9] = {0, 1, 255, 256, 1000, 32767, 32768, 65534, 65535};
    for (int i = 0; i < 9; ++i) img.pixels[std::size_t(i)] = values[i];
    write_pgm(dir / "hf.pgm", img);
    const GrayImage16 back = read_pgm(dir / "hf.pgm");
    EXPECT_EQ(back.maxval, 65535);
    EXPECT_EQ(back.image.width, 3);
    EXPECT_EQ(back.image.pixels, img.pixels);
    // 3x3 samples at two bytes plus the header "P5\n3 3\n65535\n" (13 bytes).
    EXPECT_EQ(std::filesystem::file_size(dir / "hf.pgm"), 13u + 18u);
}

TEST(Pnm, Pgm8RoundTripClampsToMaxval) {
    ScratchDir dir;
    Image2D<std::uint16_t> img(2, 1);
    img.pixels = {7, 300};
    write_pgm(dir / "a.pgm", img, 255);
    const GrayImage16 back = read_pgm(dir / "a.pgm");
    EXPECT_EQ(back.maxval, 255);
    EXPECT_EQ(back.image.pixels, (ImagePixels<std::uint16_t>{7, 255}));
}

TEST(Pnm, PpmRoundTrip) {
    ScratchDir dir;
    ColorImage img(2, 2);
    img.pixels = {Rgb8{1, 2, 3}, Rgb8{255, 0, 128}, Rgb8{10, 20, 30}, Rgb8{0, 0, 0}};
    write_ppm(dir / "color.ppm", img);
    const ColorImage back = read_ppm(dir / "color.ppm");
    EXPECT_EQ(back.width, 2);
    EXPECT_EQ(back.height, 2);
    EXPECT_EQ(back.pixels, img.pixels);
}

TEST(Pnm, Ppm16BitIsRescaledTo8) {
    // maxval 65535: 65535 -> 255, 0x8080 = 32896 -> 32896*255/65535 = 128, 0 -> 0.
    const auto b = bytes("P6\n1 1\n65535\n", {0xFF, 0xFF, 0x80, 0x80, 0x00, 0x00});
    const ColorImage c = parse_ppm(b.data(), b.size(), "color.ppm");
    EXPECT_EQ(c.pixels[0], (Rgb8{255, 128, 0}));
}

TEST(Pnm, WrongMagic) {
    const auto b = bytes("P2\n1 1\n255\n0\n");
    EXPECT_NE(problem_of([&] { pgm(b); }).find("P5"), std::string::npos);
    const auto p = bytes("P5\n1 1\n255\n", {0});
    EXPECT_NE(problem_of([&] { parse_ppm(p.data(), p.size(), "hf.pgm"); }).find("P6"), std::string::npos);
}

TEST(Pnm, MaxvalZero) {
    const auto b = bytes("P5\n1 1\n0\n", {0});
    EXPECT_NE(problem_of([&] { pgm(b); }).find("maxval 0"), std::string::npos);
}

TEST(Pnm, MaxvalTooLarge) {
    const auto b = bytes("P5\n1 1\n65536\n", {0, 0});
    EXPECT_NE(problem_of([&] { pgm(b); }).find("maxval 65536"), std::string::npos);
}

TEST(Pnm, ZeroSize) {
    const auto b = bytes("P5\n0 5\n255\n");
    EXPECT_NE(problem_of([&] { pgm(b); }).find("size 0x5"), std::string::npos);
}

TEST(Pnm, AbsurdSizeIsRejectedBeforeAllocating) {
    const auto b = bytes("P5\n70000 70000\n65535\n", {0, 0});
    EXPECT_NE(problem_of([&] { pgm(b); }).find("size 70000x70000"), std::string::npos);
    const auto huge = bytes("P5\n99999999999 2\n255\n");
    EXPECT_NE(problem_of([&] { pgm(huge); }).find("absurd"), std::string::npos);
}

TEST(Pnm, Truncated) {
    const auto b = bytes("P5\n3 3\n65535\n", {0, 1, 0, 2});
    EXPECT_NE(problem_of([&] { pgm(b); }).find("truncated"), std::string::npos);
    const auto no_raster = bytes("P5\n3 3\n255");
    EXPECT_FALSE(problem_of([&] { pgm(no_raster); }).empty());
}

TEST(Pnm, MalformedHeader) {
    const auto b = bytes("P5\nthree 3\n255\n");
    EXPECT_NE(problem_of([&] { pgm(b); }).find("width"), std::string::npos);
    const auto empty = bytes("");
    EXPECT_FALSE(problem_of([&] { pgm(empty); }).empty());
}

TEST(Pnm, MissingFileNamesThePath) {
    ScratchDir dir;
    const std::string path = dir / "nothing.pgm";
    EXPECT_NE(problem_of([&] { read_pgm(path); }, path).find("no such file"), std::string::npos);
}

TEST(Pnm, FailedWriteLeavesNothingBehind) {
    ScratchDir dir;
    Image2D<std::uint16_t> img(2, 2);
    EXPECT_THROW(write_pgm(dir / "missing-folder/hf.pgm", img), Error);
    EXPECT_THROW(write_pgm(dir / "bad.pgm", img, 0), Error);
    EXPECT_TRUE(std::filesystem::is_empty(dir.path));
}

} // namespace
} // namespace overflight
