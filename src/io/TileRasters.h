#pragma once
// Private to src/io: the GeoTIFFs of a tile directory (io/TileDirectory.h).
// Each is encoded in memory and written with write_file_atomically, so a full
// disk or an interruption never leaves a partial file under its final name;
// a re-run keeps a file only when geotiff_matches() reads back exactly what
// it would write; readers check a file's raster size, band count and type
// against the index before any buffer is sized from them.
#include "core/TileGrid.h"
#include "io/Files.h"
#include "io/Gdal.h"

#include <array>
#include <string>
#include <vector>

namespace overflight {

// One GeoTIFF: `bands` planes of cols x rows samples of `type` (band b at
// data + b * plane bytes), with a geotransform and CRS when `gt` is given,
// and for heights the index's metre mapping as band scale/offset so that GIS
// tools read metres.
struct RasterSpec {
    int cols = 0, rows = 0, bands = 1;
    GDALDataType type = GDT_UInt16;
    const void* data = nullptr;
    const std::array<double, 6>* gt = nullptr;
    std::string wkt;
    const TileGrid* height_mapping = nullptr;
    bool rgb = false;
    int levels = 0; // GeoTIFF overviews holding every 2^m-th sample, m = 1 .. levels
    // Instead of every 2^m-th sample, overview m holds box_levels[m - 1]
    // (bands planes of cols / 2^m x rows / 2^m; cols and rows multiples of
    // 2^levels): an imagery tile's mip levels. With rgb and 4 bands, band 4
    // is alpha.
    const std::vector<const void*>* box_levels = nullptr;
};

// Writes `spec` to `path` (DEFLATE GeoTIFF). Throws Error(path, ...), e.g.
// "cannot write: no space left on device"; `path` is then untouched. With
// FileSync::Later the caller's FolderSync makes it durable (io/Files.h).
void write_geotiff(const std::string& path, const RasterSpec& spec, FileSync sync = FileSync::Now);

// Whether `path` is a GeoTIFF holding exactly `spec`: raster size, bands,
// type, geotransform, height mapping and every sample of every level.
bool geotiff_matches(const std::string& path, const RasterSpec& spec);

// Opens `path` and checks that it is a raster of cols x rows samples in
// `bands` bands of `type`; Error(path, ...) otherwise.
gdal::Dataset open_checked(const std::string& path, int cols, int rows, int bands, GDALDataType type);

// Reads `bands` planes of cols x rows samples of `type` from `ds` into
// `out`; with reduce > 1 from the level holding every reduce-th sample (cols
// x rows is its size). Error(path, ...) when that level is missing or a read
// fails (a truncated file).
void read_bands(GDALDatasetH ds, const std::string& path, int cols, int rows, int bands, GDALDataType type, void* out,
                int reduce = 1);

} // namespace overflight
