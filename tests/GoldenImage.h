#pragma once
// Golden images with a per-test tolerance (DESIGN sec. 8), for the gl tests.
// Include it in one source file per test executable (it defines stb_image).
#include "core/Image.h"
#include "io/ImageWriters.h"

#define STB_IMAGE_IMPLEMENTATION
#include <stb/stb_image.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>

namespace overflight {

// Compares with tests/golden/NAME.png: at most `share` of the pixels may
// differ by more than `max_diff` in any channel. OVERFLIGHT_UPDATE_GOLDEN=1 rewrites it.
inline void expect_golden(const std::string& name, const ColorImage& img, int max_diff, double share) {
    const std::string path = std::string(OVERFLIGHT_SOURCE_DIR) + "/tests/golden/" + name + ".png";
    if (const char* u = std::getenv("OVERFLIGHT_UPDATE_GOLDEN"); u && std::string(u) == "1") {
        std::filesystem::create_directories(std::filesystem::path(path).parent_path());
        write_png(path, img);
        std::printf("updated %s\n", path.c_str());
        return;
    }
    int w = 0, h = 0, n = 0;
    unsigned char* data = stbi_load(path.c_str(), &w, &h, &n, 3);
    ASSERT_NE(data, nullptr) << "missing golden image " << path << " (run with OVERFLIGHT_UPDATE_GOLDEN=1)";
    ASSERT_EQ(w, img.width);
    ASSERT_EQ(h, img.height);
    long long over = 0;
    for (std::size_t i = 0; i < img.pixels.size(); ++i) {
        const Rgb8 p = img.pixels[i];
        const int d = std::max({std::abs(p.r - data[3 * i]), std::abs(p.g - data[3 * i + 1]), std::abs(p.b - data[3 * i + 2])});
        over += d > max_diff;
    }
    stbi_image_free(data);
    EXPECT_LE(double(over) / double(img.pixels.size()), share) << name << ": " << over << " pixels differ by more than " << max_diff;
}


} // namespace overflight
