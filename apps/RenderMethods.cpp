// The method table of `render` and `bench`. See RenderMethods.h.
//
// Based on: Szenberg et al. 1997 (voxel, Tables 1 and 2), seed 003 sec. 5
// (roam), Zamri, seed 001 (quadtree); DESIGN sec. 6.
#include "RenderMethods.h"

#include "QuadtreeMethod.h"
#include "RoamMethod.h"
#include "core/Error.h"
#include "io/SceneFile.h"
#include "lod/QuadtreeAccuracy.h"
#include "raycast/FloatingHorizon.h"
#include "raycast/FloatingHorizonLiteral.h"
#include "raycast/RayMarcher.h"

#include <algorithm>
#include <chrono>
#include <cmath>

namespace overflight::app {

RaycastOptions RenderSettings::raycast() const {
    RaycastOptions o;
    o.surface = parse_surface_model(surface, "--surface");
    o.tilt = parse_tilt_method(tilt_method, "--tilt-method");
    o.lod = lod;
    if (!(near_step >= 0.0 && near_step <= 1000.0)) throw Error("--near-step", "must be in 0..1000 pixels");
    o.near_step_pixels = near_step;
    return o;
}

void RenderSettings::validate() const {
    raycast();
    if (triangles < 2 || triangles > kRoamMaxTriangles)
        throw Error("--triangles", std::to_string(triangles) + " is outside 2.." + std::to_string(kRoamMaxTriangles));
    if (!(error_px >= 0.01 && error_px <= 1000.0)) throw Error("--error", "must be in 0.01..1000 pixels");
    tile_cache_bytes(cache_mib);
}

void add_render_settings(CLI::App& cmd, RenderSettings& s) {
    cmd.add_option("--scene", s.scene, "objects to draw besides the data set's (TOML, DESIGN sec. 5)");
    cmd.add_option("--surface", s.surface,
                   "voxel surface model: blocks (each sample a flat-topped column, the papers' voxels) or bilinear")
        ->capture_default_str();
    cmd.add_flag("--lod", s.lod,
                 "voxel distance LOD: past the distance where a pixel spans half a cell, step 2^L cells through "
                 "max-height/mean-color pyramids (faster, slightly taller distant silhouettes)");
    cmd.add_option("--tilt-method", s.tilt_method,
                   "voxel with --projection tilt: exact (vertical planes covering the tilted view, each pixel "
                   "reprojected exactly, at most a quarter pixel sideways) or guedes (Guedes' per-row ray slopes and "
                   "incremental d-buffer; approximate off the centre row)")
        ->capture_default_str();
    cmd.add_option("--near-step", s.near_step,
                   "voxel: near the eye, where a cell spans more pixels, put slices closer than one cell so that a "
                   "step spans at most this many pixels (down to 1/8 cell); 0 = one cell everywhere as in the paper")
        ->capture_default_str();
    cmd.add_option("--triangles", s.triangles, "roam: triangle budget per frame")->capture_default_str();
    cmd.add_option("--error", s.error_px, "quadtree: screen-space error target in pixels")->capture_default_str();
    cmd.add_option("--cache-mib", s.cache_mib,
                   "quadtree: memory bound of the tile cache in MiB (far tiles load reduced; a view that needs more "
                   "streams its tiles within the frame)")
        ->capture_default_str();
}

RenderSession::RenderSession(const DataSet& data, const RenderSettings& settings, std::string tile_dir)
    : data_(data), settings_(settings), tile_dir_(std::move(tile_dir)) {
    settings_.validate();
    if (!settings_.scene.empty()) extra_scene_ = load_scene(settings_.scene);
}

RenderSession::~RenderSession() = default;

GlMethods& RenderSession::gl() {
    if (!gl_) gl_ = std::make_unique<GlMethods>(data_, extra_scene_);
    return *gl_;
}

namespace {

double ms_since(std::chrono::steady_clock::time_point t0) {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

nlohmann::json raycast_stats_json(const RaycastStats& s) {
    nlohmann::json j;
    j["ms"] = {{"setup", s.ms_setup}, {"cast", s.ms_cast}, {"resolve", s.ms_resolve}, {"raycast", s.ms_total}};
    j["samples"] = s.samples;
    j["samples_visited"] = s.samples_visited;
    j["columns"] = s.columns;
    j["slices"] = s.slices;
    j["pixels_painted"] = s.pixels_painted;
    if (s.fallback_pixels) j["fallback_pixels"] = s.fallback_pixels;
    j["ns_per_sample"] = s.samples ? s.ms_total * 1e6 / double(s.samples) : 0.0;
    return j;
}

// The ray caster alone, or followed by Szenberg's composite (Fig. 5): its
// color (and depth, with objects) loaded into the framebuffer the objects
// are then drawn into with the depth test.
class VoxelRenderer : public ViewRenderer {
public:
    enum class Composite { None, Present, Objects };
    VoxelRenderer(RenderSession& s, Composite composite)
        : session_(s), fh_(s.data().terrain), options_(s.settings().raycast()),
          composite_(composite) {
        if (composite_ != Composite::None) session_.gl();
    }
    void render(const Camera& camera, ColorImage& color, DepthImage& depth, nlohmann::json& stats) override {
        RaycastStats s;
        ColorImage& cast_color = composite_ == Composite::None ? color : cast_color_;
        DepthImage& cast_depth = composite_ == Composite::None ? depth : cast_depth_;
        fh_.render(camera, session_.data().environment, options_, cast_color, cast_depth, &s);
        stats = raycast_stats_json(s);
        stats["surface"] = to_string(options_.surface);
        stats["lod"] = options_.lod;
        if (camera.projection == Projection::Tilt) stats["tilt_method"] = to_string(options_.tilt);
        if (composite_ == Composite::None) return;
        session_.gl().composite(cast_color_, cast_depth_, camera, composite_ == Composite::Objects, color,
                                session_.want_depth ? &depth : nullptr, stats);
        if (!session_.want_depth) depth = cast_depth_;
    }

private:
    RenderSession& session_;
    FloatingHorizon fh_;
    RaycastOptions options_;
    Composite composite_;
    ColorImage cast_color_;
    DepthImage cast_depth_;
};

class LiteralRenderer : public ViewRenderer {
public:
    explicit LiteralRenderer(const RenderSession& s) : data_(s.data()), options_(s.settings().raycast()) {
        if (options_.lod) throw Error("--lod", "voxel-literal has no LOD (it is Algorithm 1 as printed)");
    }
    void render(const Camera& camera, ColorImage& color, DepthImage& depth, nlohmann::json& stats) override {
        RaycastStats s;
        render_floating_horizon_literal(data_.terrain, data_.environment, camera, options_.surface, color, depth, &s);
        stats = raycast_stats_json(s);
        stats["surface"] = to_string(options_.surface);
    }

private:
    const DataSet& data_;
    RaycastOptions options_;
};

class RayMarchRenderer : public ViewRenderer {
public:
    explicit RayMarchRenderer(const RenderSession& s)
        : marcher_(s.data().terrain, s.data().environment), options_(s.settings().raycast()) {}
    void render(const Camera& camera, ColorImage& color, DepthImage& depth, nlohmann::json& stats) override {
        const auto t0 = std::chrono::steady_clock::now();
        marcher_.render(camera, options_.surface, color, depth);
        stats = {{"ms", {{"raymarch", ms_since(t0)}}},
                 {"rays", (long long)camera.width * camera.height},
                 {"surface", to_string(options_.surface)}};
    }

private:
    RayMarcher marcher_;
    RaycastOptions options_;
};

// The full mesh and Szenberg's Table 2 representations, resident in GL.
class GlTerrainRenderer : public ViewRenderer {
public:
    GlTerrainRenderer(RenderSession& s, gl::TerrainMethod m) : session_(s), method_(m) { session_.gl(); }
    void render(const Camera& camera, ColorImage& color, DepthImage& depth, nlohmann::json& stats) override {
        stats = nlohmann::json::object();
        session_.gl().render_terrain(method_, camera, color, session_.want_depth ? &depth : nullptr, stats);
    }

private:
    RenderSession& session_;
    gl::TerrainMethod method_;
};

// Split-only ROAM: the mesh rebuilt on the CPU every frame, then drawn.
class RoamRenderer : public ViewRenderer {
public:
    explicit RoamRenderer(RenderSession& s) : session_(s), roam_(make_roam(s.data().terrain)) { session_.gl(); }
    void render(const Camera& camera, ColorImage& color, DepthImage& depth, nlohmann::json& stats) override {
        const RoamMethodResult r = roam_method(roam_, camera, {session_.settings().triangles, std::nullopt});
        stats = nlohmann::json::parse(r.stats_json);
        stats["ms"] = {{"tessellate", r.ms_tessellate}};
        session_.gl().render_mesh(r.mesh, camera, color, session_.want_depth ? &depth : nullptr, stats);
        stats["ms"]["draw"] = stats["ms"]["terrain"];
    }
    void bench_extras(const Camera& camera, nlohmann::json& run) override {
        const nlohmann::json j = nlohmann::json::parse(roam_bench_json(roam_, camera));
        run["triangles_per_s"] = j["triangles_per_s"];
        run["ms_tessellate_100000"] = j["ms_tessellate_100000"];
        run["error_curve"] = j["curve"];
    }

private:
    RenderSession& session_;
    RoamMesh roam_;
};

// Röttger's quadtree over the tiles around the viewer, from the tile
// directory TERRAIN names (read lazily) or cut from the terrain in memory.
class QuadtreeRenderer : public ViewRenderer {
public:
    explicit QuadtreeRenderer(RenderSession& s)
        : session_(s), quadtree_(s.tile_dir().empty()
                                     ? QuadtreeMethod(s.data(), 257, tile_cache_bytes(s.settings().cache_mib))
                                     : QuadtreeMethod(s.tile_dir(), tile_cache_bytes(s.settings().cache_mib))) {
        session_.gl();
    }
    void render(const Camera& camera, ColorImage& color, DepthImage& depth, nlohmann::json& stats) override {
        quadtree_.build(camera, session_.settings().error_px, mesh_);
        stats = nlohmann::json::parse(quadtree_.stats_json());
        session_.gl().render_mesh(mesh_, camera, color, session_.want_depth ? &depth : nullptr, stats);
        stats["ms"]["draw"] = stats["ms"]["terrain"];
    }
    // Zamri's figures against full resolution: how many fewer triangles than
    // two per cell, and the screen-space error the --error target bounds. A
    // tile directory's full resolution is never in memory, so it has neither.
    void bench_extras(const Camera& camera, nlohmann::json& run) override {
        if (!session_.tile_dir().empty()) return;
        const Terrain& t = session_.data().terrain;
        quadtree_.build(camera, session_.settings().error_px, mesh_);
        const double full = 2.0 * double(t.rows() - 1) * double(t.cols() - 1);
        const ScreenError e = screen_space_error(mesh_, t, camera);
        run["full_resolution_triangles"] = full;
        run["triangle_reduction"] = full / double(std::max<std::size_t>(1, mesh_.triangle_count()));
        run["max_error_px"] = e.max_px;
        run["mean_error_px"] = e.mean_px;
        run["p99_error_px"] = e.p99_px;
    }

private:
    RenderSession& session_;
    QuadtreeMethod quadtree_;
    MeshArrays mesh_;
};

template <class R, class... Extra>
std::function<std::unique_ptr<ViewRenderer>(RenderSession&)> make(Extra... extra) {
    return [=](RenderSession& s) -> std::unique_ptr<ViewRenderer> { return std::make_unique<R>(s, extra...); };
}

} // namespace

const std::vector<RenderMethod>& render_methods() {
    using C = VoxelRenderer::Composite;
    using M = gl::TerrainMethod;
    static const std::vector<RenderMethod> methods = {
        {"voxel", "Floating Horizon ray caster (Szenberg 1997), parallel, exact", true, make<VoxelRenderer>(C::None)},
        {"voxel+present", "ray cast + color upload + present (Szenberg Table 1, without objects)", true,
         make<VoxelRenderer>(C::Present)},
        {"voxel+objects", "ray cast + color and depth upload + Z-buffered objects (Szenberg Table 1, Fig. 5)", true,
         make<VoxelRenderer>(C::Objects)},
        {"voxel-literal", "Szenberg's Algorithm 1 as printed, single-threaded (reference, shear only)", true,
         make<LiteralRenderer>()},
        {"raymarch", "brute-force per-pixel ray marcher (reference)", false, make<RayMarchRenderer>()},
        {"mesh", "full-resolution triangle mesh, OpenGL Z-buffer (the baseline)", true, make<GlTerrainRenderer>(M::Mesh)},
        {"points", "Szenberg Table 2 (a): a point on each top face", true, make<GlTerrainRenderer>(M::Points)},
        {"top-faces", "Szenberg Table 2 (b): the top face of each block", true, make<GlTerrainRenderer>(M::TopFaces)},
        {"front-faces", "Szenberg Table 2 (c): top and frontal faces", true, make<GlTerrainRenderer>(M::FrontFaces)},
        {"segments", "Szenberg Table 2 (d): straight line segments", true, make<GlTerrainRenderer>(M::Segments)},
        {"blocks", "Szenberg Table 2 (e): whole blocks", true, make<GlTerrainRenderer>(M::Blocks)},
        {"roam", "split-only ROAM, --triangles budget (seed 003 sec. 5)", true, make<RoamRenderer>()},
        {"quadtree", "Roettger quadtree over overlapping tiles, --error pixels (Zamri, seed 001)", true,
         make<QuadtreeRenderer>()},
    };
    return methods;
}

std::string render_method_names() {
    std::string names;
    for (const auto& m : render_methods()) names += (names.empty() ? "" : "|") + m.name;
    return names;
}

const RenderMethod& find_render_method(const std::string& name, const std::string& option) {
    for (const auto& m : render_methods())
        if (m.name == name) return m;
    throw Error(option, "unknown method '" + name + "' (known: " + render_method_names() + ")");
}

} // namespace overflight::app
