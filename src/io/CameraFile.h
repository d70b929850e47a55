#pragma once
// Camera files (DESIGN sec. 6.1): one JSON object holding a whole camera
// (DESIGN sec. 2) so that a view is rendered again exactly, with any method:
//
//   { "format": "overflight-camera", "version": 1,
//     "eye": [X, Y, Z],                         engine frame (world units)
//     "heading": D, "pitch": D, "fov": D, "projection": "shear"|"tilt",
//     "near": N, "far": F, "width": W, "height": H,
//     "map": { "crs": "EPSG:32610", "crs_name": "...",   only when georeferenced
//              "eye": [E, N, H], "eye_lonlat": [LON, LAT, H] } }
//
// Numbers are written with enough digits to read back the same doubles, so a
// camera read back is bit-identical to the one written. "eye" is what is
// read; "map" is there for people and GIS tools (a file written by hand may
// give only map.eye or map.eye_lonlat, which the caller converts).
#include "core/Camera.h"

#include <glm/vec3.hpp>

#include <optional>
#include <string>

namespace overflight {

// The map eye of a camera file: coordinates and the CRS they are in ("lonlat"
// for map.eye_lonlat, else map.crs; empty: the terrain's own CRS).
struct CameraFileMapEye {
    glm::dvec3 position{0.0};
    std::string crs;
};

struct CameraFile {
    Camera camera;                    // the fields the file gives; the others as `defaults`
    bool has_eye = false;             // "eye" given
    std::optional<CameraFileMapEye> map_eye; // map.eye / map.eye_lonlat when "eye" is absent
    std::string map_crs_name;         // map.crs_name as written
};

// Reads `path`; fields the file lacks keep their values in `defaults`.
// Throws Error(path, problem) for a missing or unreadable file, bad JSON, a
// field of the wrong type or value (the camera is validated), or no eye at all.
CameraFile read_camera_file(const std::string& path, const Camera& defaults);
// The same for a camera file's contents `text`, errors naming `subject`.
CameraFile parse_camera_file(const std::string& text, const std::string& subject, const Camera& defaults);

// Writes `camera` (and `map` when given) to `path` atomically; Error(path, ...) on failure.
struct CameraFileMap {
    std::string crs;       // "EPSG:32610"; empty when the CRS has no code (then map.eye is in the terrain's CRS)
    std::string crs_name;  // "WGS 84 / UTM zone 10N"
    glm::dvec3 eye{0.0};   // easting, northing, elevation
    glm::dvec3 eye_lonlat{0.0};
};
void write_camera_file(const std::string& path, const Camera& camera, const std::optional<CameraFileMap>& map);
// The text write_camera_file writes (JSON, ending in a newline).
std::string camera_file_text(const Camera& camera, const std::optional<CameraFileMap>& map);

} // namespace overflight
