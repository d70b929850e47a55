// Camera options (DESIGN sec. 6) shared by `render` and `bench`. See CameraOptions.h.
#include "CameraOptions.h"

#include "OptionValues.h"
#include "core/Error.h"
#include "io/MapFrame.h"

#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>

#include <algorithm>
#include <cmath>
#include <sstream>

namespace overflight::app {

namespace {

std::string num(double v) {
    std::ostringstream s;
    s << v;
    return s.str();
}

double terrain_extent(const Terrain& t) { return std::max(t.width(), t.depth()); }

std::string outside_terrain(const Terrain& t, double x, double z) {
    return "point " + num(x) + "," + num(z) + " is outside the terrain (X 0.." + num(t.width()) + ", Z 0.." +
           num(t.depth()) + ")";
}

// The ground under (x, z): the higher of the two surface models (DESIGN sec. 3:
// blocks, the nearest sample; bilinear), as renderers use either.
double ground_at(const Terrain& t, double x, double z) {
    const float cx = float(std::clamp(x, 0.0, double(t.width()))), cz = float(std::clamp(z, 0.0, double(t.depth())));
    return std::max(t.height_bilinear(cx, cz), t.height_nearest(cx, cz));
}

bool starts_with(const std::string& s, const char* prefix, std::string& rest) {
    const std::string p(prefix);
    if (s.compare(0, p.size(), p) != 0) return false;
    rest = s.substr(p.size());
    return true;
}

// Two or three comma-separated numbers.
std::vector<double> pair_or_triple(const std::string& text, const std::string& option, const char* form) {
    const long commas = std::count(text.begin(), text.end(), ',');
    return parse_list(text, option, commas == 2 ? 3 : 2, form);
}

} // namespace

void add_camera_options(CLI::App& cmd, CameraArgs& a) {
    auto* eye = cmd.add_option("--eye", a.eye, "eye position X,Y,Z (world units; X east, Y up, Z south)");
    auto* at = cmd.add_option("--at", a.at, "eye above the terrain point X,Z (with --agl)");
    eye->excludes(at);
    cmd.add_option("--agl", a.agl, "eye height above ground at --at or a map --eye without height (world units)");
    auto* heading = cmd.add_option("--heading", a.heading, "view heading in degrees (0 south, 90 east, 180 north, 270 west)");
    auto* pitch = cmd.add_option("--pitch", a.pitch, "pitch in degrees, positive looks up, |pitch| < 89");
    cmd.add_option("--look-at", a.look_at,
                   "point the view at a position (X,Z or X,Y,Z, lonlat:LON,LAT[,H], crs:E,N[,H]; on the ground "
                   "without height): sets heading and pitch so that it is at the image centre")
        ->excludes(heading)
        ->excludes(pitch);
    cmd.add_option("--crs", a.crs,
                   "plain positions of --eye, --at, --look-at are map coordinates E,N[,H] in this CRS (EPSG:n, WKT, "
                   "PROJ string; EPSG:4326 = lon,lat)");
    cmd.add_option("--camera", a.camera_file, "start from a camera file (JSON, --save-camera); other options override it");
    cmd.add_option("--projection", a.projection,
                   "shear: vertical view plane, pitch shifts the horizon (the papers' camera); tilt: the camera itself "
                   "is pitched (default shear)");
    cmd.add_option("--fov", a.fov, "horizontal field of view in degrees, (0, 180); default 60");
    cmd.add_option("--size", a.size, "image size WxH, 1..16384 each");
    cmd.add_option("--near", a.near, "near plane distance along the view axis (default: 1)");
    cmd.add_option("--far", a.far, "far plane distance along the view axis (default: the terrain's diagonal)");
}

void parse_size(const std::string& text, const std::string& option, int& width, int& height) {
    const std::size_t x = text.find_first_of("xX");
    auto parse_int = [&](const std::string& s) {
        if (s.empty() || s.size() > 9 || s.find_first_not_of("0123456789") != std::string::npos)
            throw Error(option, "'" + text + "' is not WxH (for example 1920x1080)");
        return std::stoi(s);
    };
    if (x == std::string::npos) throw Error(option, "'" + text + "' is not WxH (for example 1920x1080)");
    width = parse_int(text.substr(0, x));
    height = parse_int(text.substr(x + 1));
    if (width < 1 || height < 1 || width > 16384 || height > 16384)
        throw Error(option, "image size " + text + " is outside 1..16384 pixels per side");
}

Camera default_camera(const DataSet& data, int width, int height) {
    const Terrain& t = data.terrain;
    const double extent = terrain_extent(t);
    const double relief = std::max(double(t.max_height() - t.min_height()), 10.0 * t.h_scale());
    Camera cam;
    cam.width = width;
    cam.height = height;
    cam.fov = 60;
    cam.pitch = -12;
    cam.near = 1.0;
    cam.far = std::hypot(t.width(), t.depth()) * 1.05;
    if (data.start.given && t.contains(float(data.start.x), float(data.start.z))) {
        // An aerial view over the vehicle's start and the objects placed around
        // it: 150 cells behind it along its heading, above the relief.
        cam.heading = data.start.heading;
        cam.pitch = -14;
        const glm::dvec3 F = cam.forward();
        const double back = 150.0 * t.h_scale();
        const double x = std::clamp(data.start.x - back * F.x, 0.0, double(t.width()));
        const double z = std::clamp(data.start.z - back * F.z, 0.0, double(t.depth()));
        const double ground = std::max(t.height_bilinear(float(x), float(z)), t.height_bilinear(float(data.start.x), float(data.start.z)));
        // High enough to look over the relief ahead (an island's start is on its coast).
        cam.eye = {x, std::max(ground + 15.0 * t.h_scale(), double(t.min_height()) + 0.9 * relief), z};
    } else {
        // Above the south edge, looking north across the terrain.
        cam.heading = 180;
        cam.eye = {t.width() * 0.5, t.max_height() + 0.25 * relief, t.depth() + 0.02 * extent};
    }
    return cam;
}

Position parse_position(const std::string& text, const std::string& option, EngineForm form, const std::string& crs,
                        const DataSet& data) {
    std::string body;
    std::string in_crs = crs;
    bool map = !crs.empty();
    if (starts_with(text, "lonlat:", body)) {
        in_crs = kLonLat;
        map = true;
    } else if (starts_with(text, "crs:", body)) {
        in_crs.clear();
        map = true;
    } else {
        body = text;
    }
    Position p;
    if (!map) {
        const std::vector<double> v =
            form == EngineForm::XYZ  ? parse_list(body, option, 3, "X,Y,Z (three numbers)")
            : form == EngineForm::XZ ? parse_list(body, option, 2, "X,Z (two numbers)")
                                     : pair_or_triple(body, option, "X,Z or X,Y,Z (two or three numbers)");
        p.x = v[0];
        p.z = v.back();
        if (v.size() == 3) p.y = v[1];
        return p;
    }
    const std::vector<double> v = pair_or_triple(body, option, "E,N[,H] (two or three numbers after lonlat: or crs:)");
    const MapFrame frame(data.info, data.terrain.h_scale(), option);
    const glm::dvec2 w = frame.world_of(v[0], v[1], in_crs, option);
    p.x = w.x;
    p.z = w.y;
    if (v.size() == 3) p.y = v[2];
    return p;
}

std::optional<CameraFileMap> camera_map_of(const Camera& camera, const DataSet& data) {
    if (!data.info.georeferenced || data.info.crs_wkt.empty()) return std::nullopt;
    const MapFrame frame(data.info, data.terrain.h_scale(), data.info.source);
    CameraFileMap m;
    m.crs = frame.crs_code();
    m.crs_name = data.info.crs.empty() ? frame.crs_name() : data.info.crs;
    const glm::dvec2 en = frame.map_of_world(camera.eye.x, camera.eye.z);
    const glm::dvec2 ll = frame.lonlat_of_world(camera.eye.x, camera.eye.z);
    m.eye = {en.x, en.y, camera.eye.y};
    m.eye_lonlat = {ll.x, ll.y, camera.eye.y};
    return m;
}

Camera make_camera(const CameraArgs& a, const DataSet& data, int default_width, int default_height) {
    const Terrain& t = data.terrain;
    int width = default_width, height = default_height;
    if (!a.size.empty()) parse_size(a.size, "--size", width, height);
    Camera cam = default_camera(data, width, height);
    const bool from_file = !a.camera_file.empty() || !a.camera_text.empty();
    if (from_file) {
        const std::string subject = a.camera_text.empty() ? a.camera_file : "camera";
        const CameraFile file = a.camera_text.empty() ? read_camera_file(a.camera_file, cam)
                                                       : parse_camera_file(a.camera_text, subject, cam);
        cam = file.camera;
        if (file.map_eye) {
            const MapFrame frame(data.info, t.h_scale(), subject);
            const glm::dvec2 w =
                frame.world_of(file.map_eye->position.x, file.map_eye->position.y, file.map_eye->crs, subject);
            cam.eye = {w.x, file.map_eye->position.z, w.y};
        }
        // Another size keeps the horizontal field of view (DESIGN sec. 2's fov).
        if (!a.size.empty()) {
            cam.width = width;
            cam.height = height;
        }
    }
    if (a.projection == "shear") cam.projection = Projection::Shear;
    else if (a.projection == "tilt") cam.projection = Projection::Tilt;
    else if (!a.projection.empty()) throw Error("--projection", "'" + a.projection + "' is not shear or tilt");

    const double extent = terrain_extent(t);
    bool user_eye = false;
    std::optional<Position> ground_eye; // an eye given by its ground position, at --agl
    if (!a.eye.empty()) {
        const Position p = parse_position(a.eye, "--eye", EngineForm::XYZ, a.crs, data);
        if (p.y) {
            if (a.agl) throw Error("--agl", "applies to --at or to a map --eye without height, not to " + a.eye);
            cam.eye = {p.x, *p.y, p.z};
        } else {
            ground_eye = p;
        }
        user_eye = true;
    } else if (!a.at.empty() || a.agl) {
        Position p{cam.eye.x, cam.eye.z, std::nullopt};
        if (!a.at.empty()) {
            p = parse_position(a.at, "--at", EngineForm::XZ, a.crs, data);
            if (p.y) throw Error("--at", "'" + a.at + "' gives a height; --at takes the ground position, --agl the height above it");
            user_eye = true;
        }
        ground_eye = p;
    }
    if (ground_eye) {
        const double x = ground_eye->x, z = ground_eye->z;
        const std::string option = a.eye.empty() ? "--at" : "--eye";
        if (user_eye && !t.contains(float(x), float(z))) throw Error(option, outside_terrain(t, x, z));
        const double agl = a.agl.value_or(std::max(15.0 * t.h_scale(), 0.05 * double(t.max_height() - t.min_height())));
        if (!std::isfinite(agl) || agl < 0 || agl > 100.0 * extent)
            throw Error("--agl", num(agl) + " is not a height above ground in 0.." + num(100.0 * extent));
        cam.eye = {x, t.height_bilinear(float(std::clamp(x, 0.0, double(t.width()))),
                                        float(std::clamp(z, 0.0, double(t.depth())))) + agl, z};
    }
    // A sane eye: within 10 terrain extents of the map horizontally, and no
    // more than 100 extents above it or one extent below its lowest point.
    const double margin = 10.0 * extent;
    if (cam.eye.x < -margin || cam.eye.x > t.width() + margin || cam.eye.z < -margin || cam.eye.z > t.depth() + margin ||
        cam.eye.y < t.min_height() - extent || cam.eye.y > t.max_height() + 100.0 * extent)
        throw Error("--eye", "eye " + num(cam.eye.x) + "," + num(cam.eye.y) + "," + num(cam.eye.z) +
                                 " is too far from the terrain (X 0.." + num(t.width()) + ", Z 0.." + num(t.depth()) + ")");
    // An eye under the ground sees the inside of the terrain: one solid color.
    if (t.contains(float(cam.eye.x), float(cam.eye.z))) {
        const double ground = ground_at(t, cam.eye.x, cam.eye.z);
        if (cam.eye.y < ground)
            throw Error(ground_eye ? "--agl" : !a.eye.empty() ? "--eye" : from_file ? (a.camera_text.empty() ? a.camera_file : "camera") : "--agl",
                        "eye " + num(cam.eye.x) + "," + num(cam.eye.y) + "," + num(cam.eye.z) + " is " +
                            num(ground - cam.eye.y) + " below the terrain surface (ground at " + num(ground) +
                            " there)");
    }
    if (!a.look_at.empty()) {
        const Position p = parse_position(a.look_at, "--look-at", EngineForm::XZOrXYZ, a.crs, data);
        if (!t.contains(float(p.x), float(p.z))) throw Error("--look-at", outside_terrain(t, p.x, p.z));
        const glm::dvec3 d = glm::dvec3(p.x, p.y.value_or(t.height_bilinear(float(p.x), float(p.z))), p.z) - cam.eye;
        const double across = std::hypot(d.x, d.z);
        const double pitch = glm::degrees(std::atan2(d.y, across));
        if (!(std::abs(pitch) < 89.0))
            throw Error("--look-at", "'" + a.look_at + "' is " + num(pitch) + " degrees from the horizon seen from the eye; "
                                     "the pitch must be within (-89, 89)");
        // The image centre's ray is F + tan(p) Y for shear and F' for tilt
        // (DESIGN sec. 2): both point along d for this heading and pitch.
        cam.heading = glm::degrees(std::atan2(d.x, d.z));
        cam.pitch = pitch;
        user_eye = false; // the heading is set
    }
    if (a.heading) {
        if (!std::isfinite(*a.heading)) throw Error("--heading", "is not a number");
        cam.heading = *a.heading;
    } else if (user_eye && !from_file) { // a camera file's heading stays
        const double dx = t.width() * 0.5 - cam.eye.x, dz = t.depth() * 0.5 - cam.eye.z;
        if (std::hypot(dx, dz) > 1e-6) cam.heading = glm::degrees(std::atan2(dx, dz));
    }
    if (a.pitch) {
        if (!(std::abs(*a.pitch) < 89.0)) throw Error("--pitch", num(*a.pitch) + " is outside (-89, 89) degrees");
        cam.pitch = *a.pitch;
    }
    if (a.fov) {
        if (!(*a.fov > 0.0 && *a.fov < 180.0)) throw Error("--fov", num(*a.fov) + " is outside (0, 180) degrees");
        cam.fov = *a.fov;
    }
    if (a.near) {
        if (!(*a.near > 0.0) || !std::isfinite(*a.near)) throw Error("--near", num(*a.near) + " must be a positive distance");
        cam.near = *a.near;
    }
    if (a.far) {
        if (!std::isfinite(*a.far) || !(*a.far > cam.near))
            throw Error("--far", num(*a.far) + " must be greater than --near (" + num(cam.near) + ")");
        cam.far = *a.far;
    } else if (!(cam.far > cam.near)) {
        throw Error("--near", num(cam.near) + " must be less than --far (" + num(cam.far) + ")");
    }
    // Slices are one cell apart: a far plane of more than 2^24 cells is a typo.
    if (cam.far / t.h_scale() > 16777216.0)
        throw Error("--far", num(cam.far) + " is more than 2^24 cells (" + num(t.h_scale()) + " each) away");
    cam.validate();
    return cam;
}

} // namespace overflight::app
