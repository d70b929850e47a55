#pragma once
// Reads a PNG written by the program under test into a core ColorImage (row 0
// on top, as written). Include from one test file per executable only: it
// carries stb_image's implementation, kept static to this file.
#include "core/Image.h"

#define STB_IMAGE_STATIC
#define STB_IMAGE_IMPLEMENTATION
#include <stb/stb_image.h>

#include <string>

namespace overflight::test {

// An empty image when the file is missing or not a PNG.
inline ColorImage read_png(const std::string& path) {
    int w = 0, h = 0, n = 0;
    unsigned char* data = stbi_load(path.c_str(), &w, &h, &n, 3);
    ColorImage img;
    if (!data) return img;
    img.width = w;
    img.height = h;
    img.pixels.resize(std::size_t(w) * std::size_t(h));
    for (std::size_t i = 0; i < img.pixels.size(); ++i) img.pixels[i] = {data[3 * i], data[3 * i + 1], data[3 * i + 2]};
    stbi_image_free(data);
    return img;
}

} // namespace overflight::test
