#pragma once
// Netpbm grey maps (PGM, P5) and pixmaps (PPM, P6), the file formats of the
// hovercraft data set (CMSC 23700 project 2a, sec. 6.2 and 6.3): `hf.pgm` holds 16-bit
// heights, `color.ppm` one RGB pixel per grid cell.
//
// Based on: CMSC 23700 project 2a, sec. 6; the Netpbm format
// specification (binary rasters; a maxval above 255 means two bytes per
// sample, most significant byte first).
#include "core/Image.h"

#include <cstddef>
#include <cstdint>
#include <string>

namespace overflight {

// A PGM as read: samples widened to 16 bits, and the file's maxval.
struct GrayImage16 {
    Image2D<std::uint16_t> image;
    int maxval = 65535;
};

// Largest side accepted: a (2^16+1)-sample height field, the largest Terrain.
inline constexpr int kPnmMaxSide = 65537;

// Parses a binary PGM (P5) held in memory: header comments are allowed, maxval
// in 1..65535 (one byte per sample up to 255, two big-endian bytes above).
// Samples above maxval are kept as they are (the hovercraft data are trusted to
// match their maxval; clamping would silently change heights). Throws
// Error(subject, problem) on a wrong magic, a malformed header, maxval 0 or
// > 65535, a width or height of 0 or > kPnmMaxSide, or fewer data bytes than the
// header promises; never allocates more than the data present.
GrayImage16 parse_pgm(const std::uint8_t* data, std::size_t size, const std::string& subject);

// Parses a binary PPM (P6); maxval above 255 is rescaled to 8 bits. Same
// errors as parse_pgm.
ColorImage parse_ppm(const std::uint8_t* data, std::size_t size, const std::string& subject);

// Read a whole file and parse it; a missing or unreadable file is
// Error(path, "cannot open ...").
GrayImage16 read_pgm(const std::string& path);
ColorImage read_ppm(const std::string& path);

// Write a P5 with the given maxval (1..65535; two bytes per sample above 255,
// samples are clamped to maxval) or a P6 with maxval 255. Written to a
// temporary name beside `path` and renamed, so a failure leaves nothing behind.
void write_pgm(const std::string& path, const Image2D<std::uint16_t>& image, int maxval = 65535);
void write_ppm(const std::string& path, const ColorImage& image);

} // namespace overflight
