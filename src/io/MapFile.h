#pragma once
// The `map` file of a hovercraft data set (CMSC 23700 project 2a, sec. 6.1; DESIGN sec. 4),
// written in TOML:
//
//     h_scale = 10.0            # required: metres between samples
//     v_scale = 0.1             # required: metres per height unit
//     y_offset = 0.0            # optional: world Y of sample value 0 (DESIGN sec. 1)
//     sun_dir = [0.3, 0.8, 0.5] # towards the sun
//     sun_color = [1.0, 0.96, 0.9]
//     ambient = [0.35, 0.38, 0.45]
//     fog_density = 0.0002      # GL_EXP fog
//     fog_color = [0.72, 0.8, 0.9]
//     sky_zenith = [...]; sky_horizon = [...]
//     sea_level = 0.0           # world Y of the sea that `--water` floods to
//     [vehicle]
//     x = 100.0; z = 200.0; heading = 90.0
//     [[object]] ... / [[line]] ...  (DESIGN sec. 5, see SceneFile.h)
//
// Everything but h_scale and v_scale is optional with the defaults of
// Environment. Unknown keys are errors, so that a misspelt key is not silently
// ignored.
#include "core/DataSet.h"

#include <string>
#include <string_view>

namespace overflight {

struct MapFile {
    double h_scale = 1.0;
    double v_scale = 1.0;
    double y_offset = 0.0;  // 0 for the course's data sets; lets a DEM with sea floor be saved exactly
    Environment environment;
    VehicleStart start;
    Scene scene;
};

// Parses map text. `subject` names the file in errors ("SUBJECT: line N: ..."):
// TOML syntax errors, a missing or non-positive h_scale/v_scale, wrong-typed
// keys, unknown keys and malformed objects all throw Error(subject, ...).
// Model paths of objects are resolved against `base_dir`.
MapFile parse_map(std::string_view text, const std::string& subject, const std::string& base_dir = "");

// Reads and parses the file `path` (objects resolved against its folder).
MapFile load_map(const std::string& path);

// TOML text that parse_map reads back to the same values.
std::string format_map(const MapFile& map);

} // namespace overflight
