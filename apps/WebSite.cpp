// The static site of `overflight web` (see the header).
#include "WebSite.h"

#include "core/Error.h"
#include "core/TerrainDecimation.h"
#include "core/WebTerrainFormat.h"
#include "gl/AtmosphereGlsl.h"
#include "gl/ObjectGeometry.h"
#include "io/Files.h"
#include "sim/VehicleBody.h"

#include <nlohmann/json.hpp>

#include <cerrno>
#include <cstdlib>
#include <filesystem>
#include <string_view>
#include <system_error>
#include <vector>

namespace fs = std::filesystem;

namespace overflight::app {

namespace {

// SIMD128 and scalar builds: the page loads the one the browser runs.
const char* const kEngineFiles[] = {"overflight_engine.js", "overflight_engine.wasm", "overflight_engine_scalar.js",
                                    "overflight_engine_scalar.wasm"};
const char* const kShellFiles[] = {"index.html", "overflight.js"};

// SITE without trailing separators, so that "site/" and "site" are one folder.
fs::path site_path(const std::string& out) {
    fs::path p(out);
    while (p.has_relative_path() && p.filename().empty()) p = p.parent_path();
    return p;
}

void append_bytes(std::vector<std::uint8_t>& out, const void* data, std::size_t size) {
    const auto* p = static_cast<const std::uint8_t*>(data);
    out.insert(out.end(), p, p + size);
}

void pad4(std::vector<std::uint8_t>& out) {
    while (out.size() % 4 != 0) out.push_back(0);
}

static_assert(sizeof(WorldBox) == 24, "objects.bin stores a box as six floats");

std::vector<std::uint8_t> object_bytes(const gl::ObjectGeometry& g) {
    const MeshArrays& m = g.triangles;
    std::vector<std::uint8_t> out;
    append_bytes(out, "OFOBJ01", 8);
    const std::uint32_t counts[4] = {std::uint32_t(m.positions.size()), std::uint32_t(m.indices.size()),
                                     std::uint32_t(g.line_points.size()), std::uint32_t(g.bounds.size())};
    append_bytes(out, counts, sizeof counts);
    append_bytes(out, m.positions.data(), m.positions.size() * sizeof(glm::vec3));
    append_bytes(out, m.normals.data(), m.normals.size() * sizeof(glm::vec3));
    append_bytes(out, m.colors.data(), m.colors.size() * sizeof(Rgb8));
    pad4(out);
    append_bytes(out, m.indices.data(), m.indices.size() * sizeof(std::uint32_t));
    append_bytes(out, g.line_points.data(), g.line_points.size() * sizeof(glm::vec3));
    append_bytes(out, g.line_colors.data(), g.line_colors.size() * sizeof(Rgb8));
    pad4(out);
    append_bytes(out, g.bounds.data(), g.bounds.size() * sizeof(WorldBox));
    return out;
}

// What the page reads first: the files and their sizes (for the progress
// bar; a server may send no Content-Length) and what the site was made of.
// The lighting and the vehicle's start are in terrain.bin.
nlohmann::json site_json(const Terrain& t, const std::string& source, int decimation, std::size_t terrain_bytes,
                         const gl::ObjectGeometry& g, std::size_t object_bytes, std::size_t vehicle_bytes) {
    nlohmann::json j;
    j["generator"] = "overflight web";
    j["source"] = source;
    j["terrain"] = {{"file", "terrain.bin"}, {"bytes", terrain_bytes}, {"rows", t.rows()}, {"cols", t.cols()},
                    {"h_scale", t.h_scale()}, {"decimation", decimation}};
    j["objects"] = {{"file", "objects.bin"},
                    {"bytes", object_bytes},
                    {"vertices", g.triangles.positions.size()},
                    {"triangles", g.triangles.triangle_count()},
                    {"line_points", g.line_points.size()}};
    j["vehicle"] = {{"file", "vehicle.bin"}, {"bytes", vehicle_bytes}};
    return j;
}

void write_bytes(const fs::path& path, const std::vector<std::uint8_t>& bytes) {
    write_file_atomically(path.string(), bytes.data(), bytes.size());
}

void copy_into(const fs::path& from_dir, const char* name, const fs::path& to_dir) {
    std::error_code ec;
    fs::copy_file(from_dir / name, to_dir / name, ec);
    if (ec) throw Error((from_dir / name).string(), "cannot copy into the site: " + ec.message());
}

// A fresh folder beside `site`, removed again unless release() was called.
class TempFolder {
public:
    explicit TempFolder(const fs::path& site) {
        const fs::path parent = site.has_parent_path() ? site.parent_path() : fs::path(".");
        std::string name = (parent / ("." + site.filename().string() + ".tmp-XXXXXX")).string();
        if (!mkdtemp(name.data())) throw Error(site.string(), "cannot create a temporary folder beside it: " + errno_text(errno));
        path_ = name;
    }
    ~TempFolder() {
        std::error_code ec;
        if (!path_.empty()) fs::remove_all(path_, ec);
    }
    TempFolder(const TempFolder&) = delete;
    TempFolder& operator=(const TempFolder&) = delete;
    const fs::path& path() const { return path_; }
    void release() { path_.clear(); }

private:
    fs::path path_;
};

} // namespace

void check_web_site(const WebSiteOptions& o) {
    if (o.max_size < kMinWebSize || o.max_size > kMaxWebSize)
        throw Error("--max-size", std::to_string(o.max_size) + " is outside " + std::to_string(kMinWebSize) + " .. " +
                                      std::to_string(kMaxWebSize));
    const fs::path site = site_path(o.out);
    std::error_code ec;
    const fs::file_status st = fs::status(site, ec);
    if (fs::exists(st)) {
        if (!fs::is_directory(st)) throw Error(site.string(), "exists and is not a folder");
        if (!fs::is_empty(site, ec)) throw Error(site.string(), "exists and is not empty (give a new or empty folder)");
    } else {
        check_output_folder(site.string());
    }
    for (const char* name : kEngineFiles)
        if (!fs::is_regular_file(fs::path(o.engine_dir) / name, ec))
            throw Error((fs::path(o.engine_dir) / name).string(),
                        "the WebAssembly engine is not built (run scripts/build_web.sh)");
    for (const char* name : kShellFiles)
        if (!fs::is_regular_file(fs::path(o.shell_dir) / name, ec))
            throw Error((fs::path(o.shell_dir) / name).string(), "the page's shell is missing");
}

WebSiteReport write_web_site(const DataSet& data, const std::string& source, const WebSiteOptions& o,
                             const std::function<void(const std::string&)>& notice) {
    check_web_site(o);
    WebSiteReport report;
    const Terrain& full = data.terrain;
    report.decimation = decimation_factor(full.rows(), full.cols(), o.max_size);
    if (const std::string problem = decimation_problem(full.rows(), full.cols(), report.decimation); !problem.empty())
        throw Error(source, problem + " (--max-size " + std::to_string(o.max_size) + ")");
    DataSet site{decimate_terrain(full, report.decimation), data.environment, data.start, data.scene, data.info};
    if (report.decimation > 1)
        notice(std::to_string(full.cols()) + "x" + std::to_string(full.rows()) + " samples decimated by " +
               std::to_string(report.decimation) + " to " + std::to_string(site.terrain.cols()) + "x" +
               std::to_string(site.terrain.rows()) + " for --max-size " + std::to_string(o.max_size));
    report.rows = site.terrain.rows();
    report.cols = site.terrain.cols();
    const gl::ObjectGeometry objects = gl::build_object_geometry(site.scene, site.terrain);
    report.triangles = objects.triangles.triangle_count();

    const fs::path target = site_path(o.out);
    TempFolder temp(target);
    const std::vector<std::uint8_t> terrain = encode_web_terrain(site.terrain, site.environment, site.start);
    const std::vector<std::uint8_t> object = object_bytes(objects);
    gl::ObjectGeometry vehicle;
    vehicle.triangles = gl::player_vehicle_model();
    vehicle.bounds.push_back(vehicle_local_box());
    const std::vector<std::uint8_t> vehicle_file = object_bytes(vehicle);
    write_bytes(temp.path() / "terrain.bin", terrain);
    write_bytes(temp.path() / "objects.bin", object);
    write_bytes(temp.path() / "vehicle.bin", vehicle_file);
    const std::string json = site_json(site.terrain, source, report.decimation, terrain.size(), objects,
                                       object.size(), vehicle_file.size())
                                 .dump(1) +
                             "\n";
    write_file_atomically((temp.path() / "site.json").string(), json.data(), json.size());
    const std::string_view atmosphere = gl::kAtmosphereGlsl;
    write_file_atomically((temp.path() / "atmosphere.glsl").string(), atmosphere.data(), atmosphere.size());
    for (const char* name : kEngineFiles) copy_into(o.engine_dir, name, temp.path());
    for (const char* name : kShellFiles) copy_into(o.shell_dir, name, temp.path());
    std::error_code ec;
    for (const auto& e : fs::directory_iterator(temp.path())) report.bytes += (long long)e.file_size(ec);
    // An empty SITE (checked above) gives way to the finished one.
    if (fs::is_directory(target, ec)) fs::remove(target, ec);
    fs::rename(temp.path(), target, ec);
    if (ec) throw Error(target.string(), "cannot move the finished site into place: " + ec.message());
    fs::permissions(target, fs::perms::owner_all | fs::perms::group_read | fs::perms::group_exec |
                                fs::perms::others_read | fs::perms::others_exec, ec);
    temp.release();
    return report;
}

} // namespace overflight::app
