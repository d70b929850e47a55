#pragma once
// Private to src/io: a baseline TIFF 6.0 encoder for the small rasters of a
// tile folder, writing what GDAL's GTiff driver would hold (the same
// samples, georeferencing, GeoTIFF keys, band metadata and reduced levels)
// without its per-file cost. Tiling writes four files per tile, each with
// up to eight reduced levels; made through GDAL (create, overviews, close),
// the directories and GDAL's bookkeeping cost more CPU than DEFLATE itself.
//
// Based on: Adobe, "TIFF Revision 6.0" (sec. 2 structure, sec. 14
// differencing predictor, the Adobe DEFLATE compression 8, planar
// configuration 2); OGC GeoTIFF 1.1 (ModelPixelScale, ModelTiepoint,
// ModelTransformation; the GeoKeys themselves are taken from a one-sample
// file GDAL writes for the same CRS, once per CRS and band metadata).
#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace overflight {

// One image of a TIFF: `bands` planes of cols x rows samples (band b at
// data + b * plane bytes), `bytes` per sample, `is_float` for IEEE floats.
struct TiffImage {
    int cols = 0, rows = 0, bands = 1, bytes = 2;
    bool is_float = false;
    const void* data = nullptr;
};

// What a file states besides its images.
struct TiffMetadata {
    bool rgb = false;                      // photometric RGB; a fourth band is unassociated alpha
    const std::array<double, 6>* gt = nullptr; // GDAL geotransform, or none
    std::string wkt;                       // CRS (with gt), or empty
    // Band scale, offset and unit ("metre") as GDAL states them (GDAL_METADATA).
    bool has_mapping = false;
    double scale = 1, offset = 0;
};

// The bytes of a TIFF holding images[0] and, as reduced-resolution
// subfiles, images[1..]; DEFLATE level 1 (libdeflate), horizontal
// differencing for integer samples, one strip per band; the directories
// first, then the strips from the smallest image to images[0]. Throws
// std::runtime_error when GDAL cannot state the CRS.
std::vector<std::uint8_t> encode_tiff(const std::vector<TiffImage>& images, const TiffMetadata& meta);

} // namespace overflight
