// Based on: Szenberg et al. 1997 sec. 5 and 7 (Tables 1 and 2); DESIGN sec. 6
// (`render --method`, `--stats` as one JSON object).
#include "RenderSession.h"

#include "OptionValues.h"
#include "io/SceneFile.h"
#include "io/TileDirectory.h"

#include <string_view>
#include <utility>

namespace overflight::app {

MethodSettings MethodOptions::settings() const {
    MethodSettings s;
    s.raycast.surface = parse_surface_model(surface, "--surface");
    s.raycast.tilt = parse_tilt_method(tilt_method, "--tilt-method");
    s.raycast.lod = lod;
    s.raycast.near_step_pixels = near_step;
    s.triangles = triangles;
    s.error_px = error_px;
    s.cache_bytes = tile_cache_bytes(cache_mib);
    s.validate();
    return s;
}

void add_method_options(CLI::App& cmd, MethodOptions& o) {
    cmd.add_option("--scene", o.scene, "objects to draw besides the data set's (TOML, DESIGN sec. 5)");
    cmd.add_option("--surface", o.surface,
                   "voxel surface model: blocks (each sample a flat-topped column, the papers' voxels) or bilinear")
        ->capture_default_str();
    cmd.add_flag("--lod", o.lod,
                 "voxel distance LOD: past the distance where a pixel spans half a cell, step 2^L cells through "
                 "max-height/mean-color pyramids (faster, slightly taller distant silhouettes)");
    cmd.add_option("--tilt-method", o.tilt_method,
                   "voxel with --projection tilt: exact (vertical planes covering the tilted view, each pixel "
                   "reprojected exactly, at most a quarter pixel sideways) or guedes (Guedes' per-row ray slopes and "
                   "incremental d-buffer; approximate off the centre row)")
        ->capture_default_str();
    cmd.add_option("--near-step", o.near_step,
                   "voxel: near the eye, where a cell spans more pixels, put slices closer than one cell so that a "
                   "step spans at most this many pixels (down to 1/8 cell); 0 = one cell everywhere as in the paper")
        ->capture_default_str();
    cmd.add_option("--triangles", o.triangles, "roam: triangle budget per frame")
        ->transform(decimal<int>())
        ->capture_default_str();
    cmd.add_option("--error", o.error_px, "quadtree: screen-space error target in pixels")->capture_default_str();
    cmd.add_option("--cache-mib", o.cache_mib,
                   "quadtree: memory bound of the tile cache in MiB (far tiles load reduced; a view that needs more "
                   "streams its tiles within the frame)")
        ->transform(decimal<int>())
        ->capture_default_str();
}

std::unique_ptr<TileSet> tile_directory_tiles(const std::string& tile_dir, std::size_t memory_bound) {
    const TileIndex index = read_tile_index(tile_dir);
    auto tiles = std::make_unique<TileSet>(index.grid, tile_directory_loader(tile_dir, index), memory_bound);
    // The imagery tiles stream with the heights, within a bound of their own as large.
    if (index.imagery.present())
        tiles->set_imagery(index.imagery, tile_directory_imagery_loader(tile_dir, index), memory_bound);
    return tiles;
}

namespace {
Scene objects_of(const DataSet& data, const std::string& scene_file) {
    Scene scene = data.scene;
    if (!scene_file.empty()) scene.append(load_scene(scene_file));
    return scene;
}
} // namespace

RenderSession::RenderSession(const DataSet& data, const MethodOptions& options, std::string tile_dir)
    : data_(data), environment_(data.environment), settings_(options.settings()), scene_(objects_of(data, options.scene)),
      tile_dir_(std::move(tile_dir)), sun_shadow_(std::make_unique<SharedSunShadow>(data.terrain)),
      context_{data.terrain, settings_, {}} {
    context_.sun_shadow = sun_shadow_.get();
    if (!tile_dir_.empty())
        context_.tiles = [dir = tile_dir_, bound = settings_.cache_bytes] { return tile_directory_tiles(dir, bound); };
}

RenderSession::~RenderSession() = default;

std::unique_ptr<TerrainMethod> RenderSession::create(const MethodEntry& row) {
    std::unique_ptr<TerrainMethod> method = row.create(context_);
    if (!(method->output_kind() == MethodOutputKind::Images && row.composite == Composite::None)) make_gl();
    return method;
}

void RenderSession::make_gl() {
    if (gl_) return;
    gl_ = std::make_unique<gl::HeadlessRenderer>(data_.terrain, scene_);
    gl_->compositor().share_sun_shadow(sun_shadow_.get());
}

void RenderSession::render(const MethodEntry& row, TerrainMethod& method, const Camera& camera, bool want_depth,
                           RenderedView& view) {
    view.output = method.produce(MethodView{camera, environment_, std::nullopt}, view.method);
    const MethodOutput& out = view.output;
    view.composited = !(out.kind == MethodOutputKind::Images && row.composite == Composite::None);
    if (!view.composited) {
        view.color = out.color;
        view.depth = want_depth ? out.depth : nullptr;
        return;
    }
    make_gl();
    gl::CompositeOptions options;
    options.objects = out.kind != MethodOutputKind::Images || row.composite == Composite::Objects;
    gl_->render(out, camera, environment_, options, color_, want_depth ? &depth_ : nullptr, &view.gl);
    view.color = &color_;
    view.depth = want_depth ? &depth_ : nullptr;
}

void RenderSession::take_images(TerrainMethod& method, RenderedView& view, ColorImage& color, DepthImage* depth) {
    if (!view.depth) depth = nullptr;
    if (view.composited) {
        std::swap(color, color_);
        if (depth) std::swap(*depth, depth_);
    } else if (!method.swap_images(color, depth)) {
        color = *view.color;
        if (depth) *depth = *view.depth;
    }
    view.color = nullptr;
    view.depth = nullptr;
}

namespace {

void add_raycast(const RaycastStats& s, const MethodSettings& settings, const Camera& camera, nlohmann::json& j) {
    j["ms"]["setup"] = s.ms_setup;
    j["ms"]["cast"] = s.ms_cast;
    j["ms"]["resolve"] = s.ms_resolve;
    j["samples"] = s.samples;
    j["samples_visited"] = s.samples_visited;
    j["columns"] = s.columns;
    j["slices"] = s.slices;
    j["pixels_painted"] = s.pixels_painted;
    if (s.fallback_pixels) j["fallback_pixels"] = s.fallback_pixels;
    j["ns_per_sample"] = s.samples ? s.ms_total * 1e6 / double(s.samples) : 0.0;
    j["lod"] = settings.raycast.lod;
    if (camera.projection == Projection::Tilt) j["tilt_method"] = to_string(settings.raycast.tilt);
}

void add_roam(const RoamStats& s, const MethodSettings& settings, const MethodStats& m, nlohmann::json& j) {
    j["method"] = "roam";
    j["vertices"] = s.vertices;
    j["ms_tessellate"] = m.step_ms("tessellate");
    j["max_error_px"] = s.max_error_px;
    j["mean_error_px"] = s.mean_error_px;
    j["budget"] = settings.triangles;
    j["splits"] = s.splits;
    j["forced_splits"] = s.forced_splits;
}

void add_tiles(const TileFrameStats& s, const MethodSettings& settings, nlohmann::json& j) {
    j["method"] = "quadtree";
    j["error_px"] = settings.error_px;
    j["tiles_candidates"] = s.candidates;
    j["tiles_visible"] = s.visible;
    j["tiles_culled"] = s.culled;
    j["tiles_loaded"] = s.loaded;
    j["tiles_cached"] = s.cached;
    j["tiles_evicted"] = s.evicted;
    j["tiles_streamed"] = s.streamed;
    j["tiles_per_level"] = s.per_level;
    j["rings"] = s.rings;
    j["cache_mib"] = double(s.cache_bytes) / (1024.0 * 1024.0);
    j["bound_mib"] = double(settings.cache_bytes) / (1024.0 * 1024.0);
    j["ms"]["select"] = s.ms_select;
    j["ms"]["load"] = s.ms_load;
    j["ms"]["refine"] = s.ms_refine;
    j["ms"]["fans"] = s.ms_fans;
}

} // namespace

nlohmann::json view_stats_json(const MethodSettings& settings, const Camera& camera,
                               const RenderedView& view) {
    nlohmann::json j = nlohmann::json::object();
    const MethodStats& m = view.method;
    j["ms"] = nlohmann::json::object();
    for (const MethodStep& s : m.steps) j["ms"][s.name] = s.ms;
    if (m.raycast) add_raycast(*m.raycast, settings, camera, j);
    if (m.raycast || m.rays) j["surface"] = to_string(settings.raycast.surface);
    if (m.rays) j["rays"] = m.rays;
    if (m.roam) add_roam(*m.roam, settings, m, j);
    if (m.tiles) add_tiles(*m.tiles, settings, j);
    if (m.roam || m.tiles) j["triangles"] = m.triangles;
    if (!view.composited) return j;
    j["gl_renderer"] = gl::Context::renderer();
    for (const auto& [name, ms] : view.gl.steps_ms) j["ms"][name] = ms;
    j["ms"]["gl_total"] = view.gl.total_ms();
    j["object_triangles"] = view.gl.counts.object_triangles;
    if (!m.roam && !m.tiles && !m.raycast) j["triangles"] = view.gl.counts.terrain_primitives;
    if (view.gl.counts.chunks_total > 0) {
        j["chunks_drawn"] = view.gl.counts.chunks_drawn;
        j["chunks_total"] = view.gl.counts.chunks_total;
    }
    return j;
}

} // namespace overflight::app
