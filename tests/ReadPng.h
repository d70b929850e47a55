#pragma once
// Reads a PNG written by the program under test as 8-bit RGB (row 0 on top).
// Include from one test file per executable only: it carries stb_image's
// implementation, kept static to that file.
#define STB_IMAGE_STATIC
#define STB_IMAGE_IMPLEMENTATION
#include <stb/stb_image.h>

#include <string>
#include <vector>

namespace overflight::test {

struct Png {
    int w = 0, h = 0;
    std::vector<unsigned char> rgb; // w * h * 3 bytes
    bool empty() const { return rgb.empty(); }
    const unsigned char* at(int x, int y) const { return &rgb[(std::size_t(y) * std::size_t(w) + std::size_t(x)) * 3]; }
};

// An empty Png when the file is missing or not a PNG.
inline Png read_png(const std::string& path) {
    Png p;
    int n = 0;
    if (unsigned char* data = stbi_load(path.c_str(), &p.w, &p.h, &n, 3)) {
        p.rgb.assign(data, data + std::size_t(p.w) * std::size_t(p.h) * 3);
        stbi_image_free(data);
    }
    return p;
}

} // namespace overflight::test
