#pragma once
// Private to src/io: what a GDAL source raster means to Overflight, shared by
// the loader (io/GdalRaster.h) and the windowed tiler (io/WindowedTiler.h):
// the checks made before any sample is read, the warnings about its bands,
// the metres of its vertical unit and the UTM zone a geographic raster is
// warped to (DESIGN sec. 4).
//
// Based on: Zamri, sec. 3 (USGS DEM ingestion: Record A header, elevation
// profiles).
#include <gdal.h>
#include <ogr_srs_api.h>

#include <memory>
#include <string>
#include <vector>

namespace overflight {

// Marks no-data inside our float buffers: far below any elevation on Earth,
// exactly representable, and distinct from every source's own no-data value.
inline constexpr float kNoData = -1.0e30f;

// How far GDALFillNodata searches for the valid neighbours of a no-data
// sample before a void is filled otherwise (io/GdalRaster.h): enough for SRTM
// voids and for the wedges a UTM reprojection leaves at the corners of a
// 1-degree tile. The fill of a sample reads only the samples this close.
inline constexpr int kFillSearchDistance = 256;

// The gdalwarp options, after the target grid's, of a reprojection onto
// square metric cells: bilinear, Float32 with kNoData outside the source.
// Used for the grid gdalwarp suggests and for a decimated load; a full
// resolution load and the windowed tiler warp through io/MetricWarp.h.
std::vector<std::string> metric_warp_options();

struct SrsCloser {
    void operator()(OGRSpatialReferenceH s) const { if (s) OSRDestroySpatialReference(s); }
};
using Srs = std::unique_ptr<void, SrsCloser>;

// Record A of a USGS DEM: the file's first 1024 bytes (Zamri, sec. 3).
std::string usgs_record_a_text(const std::string& path);

// The sizes a raster declares, checked before anything is allocated from
// them, since a few bytes of header can claim billions of samples (a sparse
// GeoTIFF, a USGS Record A with a false profile count): at least 2x2 samples,
// at most max_side per side (0: no limit), and a USGS DEM whose Record A
// declares more profiles than max_side or than the file holds is refused.
// Throws Error(path, ...).
void check_declared_size(GDALDatasetH ds, const std::string& path, int max_side);

// Appends to `warnings` what a user should know about the bands: only band 1
// is read as heights (a palette, or several bands).
void append_band_warnings(GDALDatasetH ds, std::vector<std::string>& warnings);

// Metres per vertical unit from GDAL's band unit type (free text in
// practice); `name` receives the unit's name for reports.
double metres_per_unit(const std::string& unit, std::string& name);

// The CRS as WKT.
std::string to_wkt(OGRSpatialReferenceH srs);

// `wkt` as a GDAL dataset given it reports it (GDALSetProjection, then
// GDALGetProjectionRef): the CRS the loader and the windowed tiler record
// for a warped grid, the same string from both.
std::string warped_crs_wkt(const std::string& wkt);

// The UTM zone of (lon, lat) on the datum of the geographic `src`: EPSG codes
// for WGS 84, otherwise the datum is kept so no datum shift is introduced.
Srs utm_for(OGRSpatialReferenceH src, double lon, double lat);

} // namespace overflight
