#pragma once
// The static site of `overflight web` (DESIGN sec. 6.1): everything a browser
// needs to fly over a terrain with no server beyond one serving files
// (`python3 -m http.server -d SITE`), in one folder:
//
//   index.html, overflight.js      the page and its shell (web/shell/, plain
//                                  JavaScript: WebGL2 composite, keys, HUD)
//   overflight_engine.js, .wasm    the core compiled by scripts/build_web.sh
//   overflight_engine_scalar.*     (ray caster, hovercraft, chase camera), with
//                                  SIMD128 and without
//   terrain.bin                    the terrain, its colors, environment and
//                                  the vehicle's start (core/WebTerrainFormat.h,
//                                  "OFTERR01")
//   objects.bin                    the scene's objects as triangle and line
//                                  arrays (format below), drawn by WebGL2
//   vehicle.bin                    the player's hovercraft in its own frame
//                                  (gl/ObjectGeometry.h player_vehicle_model,
//                                  same format, its box as the one bound),
//                                  which the page places where the engine
//                                  says (sim/VehicleBody.h)
//   atmosphere.glsl                the aerial perspective and sky of the
//                                  native shaders (gl/AtmosphereGlsl.h), which
//                                  the page's shaders include
//   site.json                      the files' sizes (the progress bar), the
//                                  source and its decimation
//
// objects.bin, little-endian, every array starting on a 4-byte boundary:
//   char[8]  "OFOBJ01\0"
//   uint32   V (vertices of the solids), I (indices), L (line points), B (boxes)
//   float32  positions[3V], normals[3V]  world coordinates, unit normals
//   uint8    colors[3V]                  padded with zeros to a multiple of 4
//   uint32   indices[I]                  triangle list
//   float32  line_points[3L]             segment k = points 2k, 2k+1
//   uint8    line_colors[3L]             padded to a multiple of 4
//   float32  boxes[6B]                   lo x, y, z, hi x, y, z: the world
//                                        bounds of the objects' pieces
//                                        (ObjectGeometry::bounds), which the
//                                        page's depth upload is limited to
// They are gl/ObjectGeometry's arrays, built on the terrain as the site holds
// it, so that the page draws what the native compositor draws.
#include "core/DataSet.h"

#include <functional>
#include <string>

namespace overflight::app {

struct WebSiteOptions {
    std::string out;        // SITE: must not exist, or be an empty folder; its parent must exist
    int max_size = 4097;    // samples per side the site's terrain holds at most (decimated beyond)
    std::string engine_dir; // holds overflight_engine{,_scalar}.{js,wasm}
    std::string shell_dir;  // holds index.html and overflight.js
};

// The smallest and largest --max-size: 65 to 8193 samples per side (8193^2
// samples are 336 MB in the page, whose engine's heap ends at 2 GB; the ray
// caster's tables and the page's own copies need their share).
inline constexpr int kMinWebSize = 65;
inline constexpr int kMaxWebSize = 8193;

struct WebSiteReport {
    int rows = 0, cols = 0;  // the site's terrain
    int decimation = 1;      // each site sample stands for decimation^2 loaded ones
    long long bytes = 0;     // the site's size
    long long triangles = 0; // the objects'
};

// Checks what can be checked before any work (options.out's state, the
// engine and shell files, max_size): Error naming the folder, file or option.
void check_web_site(const WebSiteOptions& options);

// Writes the site of `data` (objects: its scene) into a temporary folder
// beside options.out and renames it into place, so that a failure leaves
// nothing behind. A terrain with more than max_size samples on a side is
// decimated (core/TerrainDecimation.h); `notice` is called with one line
// saying so. Throws Error(subject, problem): `source` names the terrain.
WebSiteReport write_web_site(const DataSet& data, const std::string& source, const WebSiteOptions& options,
                             const std::function<void(const std::string&)>& notice);

} // namespace overflight::app
