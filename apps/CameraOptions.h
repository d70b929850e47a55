#pragma once
// The camera options of DESIGN sec. 6 shared by `render` and `bench`.
//
//   --eye X,Y,Z | --at X,Z [--agl M]   where the eye is (world units)
//   --heading D --pitch D              DESIGN sec. 1 convention, pitch > 0 looks up
//   --look-at POSITION                 heading and pitch that put POSITION at the image centre
//   --projection shear|tilt --fov D --size WxH --near N --far F
//   --camera FILE                      a camera file (io/CameraFile.h); the options above override its fields
//   --crs CRS                          plain positions are map coordinates in CRS (EPSG:n, ...)
//
// Positions (DESIGN sec. 6.1) are engine coordinates, `lonlat:LON,LAT[,H]`
// (WGS 84) or `crs:E,N[,H]` (the terrain's CRS), H the elevation in the data
// set's vertical units; a map position without H is at --agl above the ground
// for --eye and on the ground for --look-at.
//
// Without --eye/--at/--camera the camera is the data set's overview (see
// default_camera); without --heading an eye given by the user looks at the
// terrain's centre. A camera file whose size differs from --size keeps its
// horizontal field of view: the vertical one follows the new aspect ratio.
// Bad values throw overflight::Error naming the option.
#include "core/Camera.h"
#include "core/DataSet.h"
#include "io/CameraFile.h"

#include <CLI/CLI.hpp>

#include <optional>
#include <string>

namespace overflight::app {

struct CameraArgs {
    std::string eye;        // "X,Y,Z"
    std::string at;         // "X,Z"
    std::optional<double> agl, heading, pitch, fov, near, far;
    std::string projection; // "shear" (default) or "tilt"
    std::string size;       // "WxH"
    std::string look_at;    // a position
    std::string crs;        // --crs: the CRS of plain positions
    std::string camera_file; // --camera FILE
    std::string camera_text; // a camera file's contents given directly (the Python module's camera dict)
};

// A position of the command line in the engine frame: X, Z and the height
// (world Y) when the text gave one.
struct Position {
    double x = 0, z = 0;
    std::optional<double> y;
};

// The engine coordinates a position option takes.
enum class EngineForm { XZ, XYZ, XZOrXYZ };

// `text` as a position for `option`: engine coordinates of `form`,
// "lonlat:LON,LAT[,H]", "crs:E,N[,H]", or a plain "E,N[,H]" in `crs` when it
// is not empty. Throws Error(option, ...) for a malformed text or a map
// position on a terrain without georeferencing.
Position parse_position(const std::string& text, const std::string& option, EngineForm form, const std::string& crs,
                        const DataSet& data);

// Adds the options above to `cmd`; `args` must outlive the parse.
void add_camera_options(CLI::App& cmd, CameraArgs& args);

// The overview a user gets without camera options: from the vehicle's start
// (150 cells behind it along its heading, at 90 % of the relief, pitched down
// 14 degrees) when the data set has one, else above the terrain's south edge
// looking north across it, pitched down 12 degrees; far enough to see the
// whole terrain.
Camera default_camera(const DataSet& data, int width, int height);

// The camera of `args` for `data` (default size when --size is absent),
// validated. Throws Error("--fov", ...), Error("--size", ...), Error("--eye", ...) etc.
Camera make_camera(const CameraArgs& args, const DataSet& data, int default_width, int default_height);

// The map coordinates of `camera`'s eye for a camera file, or nothing when
// the data set is not georeferenced.
std::optional<CameraFileMap> camera_map_of(const Camera& camera, const DataSet& data);

// "WxH" with 1 <= W, H <= 16384; throws Error(option, ...).
void parse_size(const std::string& text, const std::string& option, int& width, int& height);

} // namespace overflight::app
