#pragma once
// The camera options of DESIGN sec. 6 shared by `render` and `bench`.
//
//   --eye X,Y,Z | --at X,Z [--agl M]   where the eye is (world units)
//   --heading D --pitch D              DESIGN sec. 1 convention, pitch > 0 looks up
//   --projection shear|tilt --fov D --size WxH --near N --far F
//
// Without --eye/--at the camera is the data set's overview (see
// default_camera); without --heading an eye given by the user looks at the
// terrain's centre. Bad values throw overflight::Error naming the option.
#include "core/Camera.h"
#include "core/DataSet.h"

#include <CLI/CLI.hpp>

#include <optional>
#include <string>

namespace overflight::app {

struct CameraArgs {
    std::string eye;        // "X,Y,Z"
    std::string at;         // "X,Z"
    std::optional<double> agl, heading, pitch, fov, near, far;
    std::string projection = "shear";
    std::string size;       // "WxH"
};

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

// "WxH" with 1 <= W, H <= 16384; throws Error(option, ...).
void parse_size(const std::string& text, const std::string& option, int& width, int& height);

} // namespace overflight::app
