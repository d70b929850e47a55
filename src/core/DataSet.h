#pragma once
// Everything a terrain argument resolves to (DESIGN sec. 4): the terrain, its
// lighting and fog, where the vehicle starts, the objects on it, and a record
// of how it was obtained (for `overflight info`).
#include "core/Scene.h"
#include "core/Terrain.h"

#include <glm/vec3.hpp>

#include <array>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace overflight {

// An exponential-height atmosphere (Hoffman, Preetham, "Rendering Outdoor
// Light Scattering in Real Time", GDC 2002, with their constant density made
// exp(-y / scale_height)): air and haze as one mixture whose extinction equals
// its scattering, Rayleigh-like per channel plus grey haze (Mie), in units of
// 1 / world unit at height 0. core/AerialPerspective.h evaluates it.
struct AtmosphereParams {
    glm::vec3 rayleigh{11.6e-6f, 27.0e-6f, 66.2e-6f}; // twice sea-level air's (Bucholtz 1995), for a thicker scale height
    float haze = 1.2e-5f;          // Mie scattering of the haze, every channel
    float scale_height = 4000.0f;  // density exp(-y / scale_height), y world height
    float haze_g = 0.7f;           // Henyey-Greenstein asymmetry of the haze
    float exposure = 2.0f;         // in-scattered sunlight to display: 1 - exp(-exposure L), then gamma 2.2
    glm::vec3 sunlight{1.0f, 1.0f, 1.0f}; // above the atmosphere (the lighting's sun_color may be switched off)
};

struct Environment {
    glm::vec3 sun_dir{0.3f, 0.8f, 0.5f};   // towards the sun, world space (normalised on use)
    glm::vec3 sun_color{1.0f, 0.96f, 0.9f};
    glm::vec3 ambient{0.35f, 0.38f, 0.45f};
    bool shadows = false;                  // the terrain casts shadows for sun_dir (core/HorizonSweep.h)
    bool baked = false;                    // the terrain's colors shown as they are, no sun on them (objects stay lit)
    float fog_density = 0.0f;              // GL_EXP fog: f = exp(-density * distance)
    glm::vec3 fog_color{0.72f, 0.80f, 0.90f};
    glm::vec3 sky_zenith{0.30f, 0.50f, 0.85f};
    glm::vec3 sky_horizon{0.72f, 0.80f, 0.90f};
    // Aerial perspective and a sky that follows the sun (AtmosphereParams)
    // instead of the GL_EXP fog and the sky gradient above.
    bool atmosphere = false;
    AtmosphereParams air;
    // A reflective water surface at world height water_level (core/WaterSurface.h),
    // its waves as they are water_time seconds into the flight.
    bool water = false;
    float water_level = 0.0f;
    double water_time = 0.0;
    // The data set's sea level (the map's `sea_level` key), if it gives one:
    // what `--water` alone floods to.
    std::optional<float> sea_level;
};

struct VehicleStart {
    bool given = false;   // false: the caller picks (terrain centre)
    double x = 0, z = 0;
    double heading = 0;   // degrees
};

// Provenance of a loaded terrain, reported by `overflight info`.
struct TerrainInfo {
    std::string source;            // path or "demo"
    std::string kind;              // "hovercraft", "gdal", "demo", "tiles"
    std::string driver;            // GDAL driver short name, or "PGM"
    std::string crs;               // WKT name of the CRS, empty if none
    std::string source_crs;        // before reprojection
    bool reprojected = false;
    std::string reprojection;      // what was done, e.g. "EPSG:4326 -> UTM 10N (EPSG:32610), bilinear, 83.2 m"
    std::string vertical_units = "metre";
    double unit_to_metre = 1.0;
    long long nodata_filled = 0;
    std::string nodata_method;     // how no-data was filled
    std::string color_source;      // "color.ppm", a raster path, "elevation ramp + hillshade", "procedural"
    int source_rows = 0, source_cols = 0;
    // Each terrain sample stands for decimation x decimation source samples
    // (a raster larger than a direct render takes, read decimated); 1: full resolution.
    int decimation = 1;
    // Georeferencing of the terrain grid as loaded (after any reprojection),
    // GDAL convention: sample (row i, col j) is the pixel whose top-left
    // corner is (gt[0] + j gt[1] + i gt[2], gt[3] + j gt[4] + i gt[5]) in
    // crs_wkt's units. `tile` copies it into every tile, offset to the tile.
    bool georeferenced = false;
    std::array<double, 6> geotransform{0, 1, 0, 0, 0, 1};
    std::string crs_wkt; // empty if none
    std::vector<std::pair<std::string, std::string>> metadata; // GDAL metadata (USGS Record A fields, ...)
    // Surprises a user should hear of although the terrain loaded, e.g. an RGB
    // image given as a DEM (band 1 taken as heights). `info` lists them, other
    // commands print them on stderr.
    std::vector<std::string> warnings;
};

struct DataSet {
    Terrain terrain;
    Environment environment;
    VehicleStart start;
    Scene scene;
    TerrainInfo info;
};

} // namespace overflight
