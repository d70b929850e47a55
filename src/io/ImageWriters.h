#pragma once
// Writers for what the renderers produce: the picture (PNG, RGB8) and the
// window-depth buffer (DESIGN sec. 6: `--depth depth.tif`, single-band
// float32 TIFF). Both write to a temporary name in the destination folder and
// rename it, checking every write and the close, so a failure (a full disk
// included) leaves nothing behind and an existing file untouched (DESIGN sec. 6).
#include "core/Image.h"

#include <string>

namespace overflight {

// RGB8 PNG through stb_image_write; row 0 is the top of the picture.
// Throws Error(path, ...) for an empty image, a missing folder or when the file
// cannot be written ("cannot write: no space left on device").
void write_png(const std::string& path, const ColorImage& image);

// Single-band Float32 GeoTIFF through GDAL (no georeferencing: the depth
// buffer lives in image space); row 0 is the top row.
void write_depth_tiff(const std::string& path, const DepthImage& depth);

} // namespace overflight
