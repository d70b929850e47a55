#pragma once
// "OFTERR01": the terrain of a web page (`overflight web`) as one file the
// page fetches and the WebAssembly engine decodes: the height field, its
// per-sample colors, the environment the ray caster paints with and the
// vehicle's start. Encoded and decoded in memory here (the core has no file
// I/O), so the native writer and the page's reader are the same code.
//
// Layout, little-endian, no padding (offsets in bytes):
//     0  char[8]  magic "OFTERR01"
//     8  int32    rows, int32 cols (2..65537 each)
//    16  float32  h_scale, v_scale, y_offset, sea_level (NaN: none)
//    32  uint32   flags: 1 shadows, 2 baked lighting, 4 atmosphere, 8 water,
//                 16 vehicle start given
//    36  float32  sun_dir[3], sun_color[3], ambient[3], fog_density,
//                 fog_color[3], sky_zenith[3], sky_horizon[3], water_level
//   116  float32  atmosphere: rayleigh[3], haze, scale_height, haze_g,
//                 exposure, sunlight[3]
//   156  float64  vehicle start x, z, heading (degrees)
//   180  uint16   heights, rows * cols, row-major (row 0 = north)
//        uint8    colors, rows * cols RGB triples, row-major
// Imagery finer than the samples is not stored: the colors are the terrain's
// per-sample colors (the imagery averaged, where it has one).
#include "core/DataSet.h"
#include "core/Terrain.h"

#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace overflight {

inline constexpr char kWebTerrainMagic[8] = {'O', 'F', 'T', 'E', 'R', 'R', '0', '1'};
inline constexpr std::size_t kWebTerrainHeaderBytes = 180;

// What the file holds.
struct WebTerrain {
    Terrain terrain;
    Environment environment; // water_time is not stored (0)
    VehicleStart start;
};

// The file's size for rows x cols samples.
std::uint64_t web_terrain_bytes(int rows, int cols);

// The file for `terrain`, `environment` and `start`.
std::vector<std::uint8_t> encode_web_terrain(const Terrain& terrain, const Environment& environment,
                                             const VehicleStart& start);

// True when `bytes` begin with the magic.
bool is_web_terrain(std::span<const std::uint8_t> bytes);

// Decodes a file. Throws Error(name, problem) for anything that is not a
// whole, valid file: another magic, a truncated or overlong file, sizes
// outside 2..65537, a scale or an environment value that is not a finite
// number, a start that is not finite.
WebTerrain decode_web_terrain(std::span<const std::uint8_t> bytes, const std::string& name = "terrain file");

} // namespace overflight
