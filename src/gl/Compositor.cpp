// Based on: Szenberg et al. 1997 sec. 3, 5 (Fig. 5) and 7 (Tables 1 and 2);
// CMSC 23700 hovercraft project sec. 3-4.
#include "gl/Compositor.h"

#include "core/Error.h"
#include "core/ShadowPixels.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <vector>

namespace overflight::gl {

namespace {

BlockMethod block_method(ResidentSurface s) {
    switch (s) {
    case ResidentSurface::Points: return BlockMethod::Points;
    case ResidentSurface::TopFaces: return BlockMethod::TopFaces;
    case ResidentSurface::FrontFaces: return BlockMethod::FrontFaces;
    case ResidentSurface::Segments: return BlockMethod::Segments;
    default: return BlockMethod::Blocks;
    }
}

void depth_test_on() {
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glDepthMask(GL_TRUE);
    glDisable(GL_CULL_FACE);
    glFrontFace(GL_CCW);
    glPolygonMode(GL_FRONT_AND_BACK, GL_FILL);
}

} // namespace

Compositor::Compositor(const Terrain& terrain, const Scene& scene) : terrain_(terrain), vehicle_(terrain) {
    block_rows_ = (terrain.rows() + kFloorBlock - 1) / kFloorBlock;
    block_cols_ = (terrain.cols() + kFloorBlock - 1) / kFloorBlock;
    block_min_.assign(std::size_t(block_rows_) * std::size_t(block_cols_), std::numeric_limits<float>::max());
    for (int row = 0; row < terrain.rows(); ++row) {
        float* blocks = block_min_.data() + std::size_t(row / kFloorBlock) * std::size_t(block_cols_);
        for (int col = 0; col < terrain.cols(); ++col)
            blocks[col / kFloorBlock] = std::min(blocks[col / kFloorBlock], terrain.sample_height(row, col));
    }
    terrain_min_ = *std::min_element(block_min_.begin(), block_min_.end());
    objects_.set_scene(scene, terrain);
    object_texel_ = ObjectShadowMap::texel_bound(objects_.bounds(), ObjectShadowMap::kSize);
    snap_ = ShadowCeilingTexture::grid(terrain);
    snap_bounds_ = HeightBounds(terrain, snap_.stride);
    if (const ImageryPyramid* imagery = terrain.imagery()) imagery_texture_.upload(*imagery);
}

void Compositor::prepare(ResidentSurface surface) {
    if (surface == ResidentSurface::Mesh) {
        if (!mesh_) mesh_ = std::make_unique<TerrainMesh>(terrain_);
    } else if (!blocks_) {
        blocks_ = std::make_unique<BlockTerrain>(terrain_);
    }
}

glm::vec4 Compositor::terrain_shadow(const Environment& environment, StepTimer& timer) {
    const glm::vec3 sun = glm::length(environment.sun_dir) > 0 ? glm::normalize(environment.sun_dir) : glm::vec3(0, 1, 0);
    // A sun at or below the horizon lights nothing (shade()): nothing to sweep.
    if (!environment.shadows || !(sun.y > 0)) return glm::vec4(0.0f);
    if (!shadow_valid_ || shadow_for_ != sun) {
        const auto t0 = std::chrono::steady_clock::now();
        if (shared_shadow_) {
            shadow_texture_.upload(shared_shadow_->get(sun)->ceiling, terrain_);
        } else {
            sweep_shadow_ceiling(terrain_, sun, shadow_);
            shadow_texture_.upload(shadow_, terrain_);
        }
        shadow_valid_ = true;
        shadow_for_ = sun;
        timer.cpu_step_since("shadow_sweep", t0);
    }
    shadow_texture_.bind();
    return shadow_texture_.uniform();
}

void Compositor::begin(const Camera& camera, const Environment& environment, const RenderTarget& target,
                       StepTimer& timer, const CompositeOptions& options) {
    camera.validate();
    if (camera.width != target.width() || camera.height != target.height())
        throw Error("camera", "image size differs from the render target");
    const glm::vec4 shadow = terrain_shadow(environment, timer);
    frame_.set_shadow(shadow);
    imagery_texture_.bind();
    frame_.set_imagery(imagery_texture_.uniform());
    frame_.update(camera, environment, terrain_);
    const glm::vec3 sun(frame_.block().sun_dir);
    object_shadow_.update(shadow.x > 0, sun, objects_, frame_.block());
    object_shadow_.bind();
    const bool moved = options.vehicle && vehicle_.place(options.vehicle->x, options.vehicle->z, options.vehicle->heading);
    vehicle_shadow_.update(shadow.x > 0 && options.vehicle, sun, vehicle_.bounds(), moved, [&] { vehicle_.draw(); },
                           frame_.block());
    vehicle_shadow_.bind();
    frame_.bind();
    target.bind();
    depth_test_on();
}

CompositeCounts Compositor::draw(const MethodOutput& out, const Camera& camera, const Environment& environment,
                                 RenderTarget& target, StepTimer& timer, const CompositeOptions& options) {
    if (out.kind == MethodOutputKind::Images && (!out.color || !out.depth))
        throw Error("compositor", "an image method produced no color or depth");
    return compose(&out, -1, camera, environment, target, timer, options);
}

int Compositor::acquire_slot(const Camera& camera) {
    stream_.reserve(camera.width, camera.height);
    const int slot = next_slot_;
    next_slot_ = (next_slot_ + 1) % ImageStream::kSlots;
    stream_.acquire(slot);
    return slot;
}

void Compositor::stage(int slot, const MethodOutput& out, const Camera& camera, const Environment& environment,
                       const CompositeOptions& options) {
    if (out.kind != MethodOutputKind::Images || !out.color || !out.depth)
        throw Error("compositor", "only an image method's color and depth can be staged");
    stream_.stage_color(slot, *out.color);
    if (!options.objects) return;
    ShadowReach& reach = staged_reach_[std::size_t(slot)];
    object_shadow_reach(camera, environment, options, out.depth, reach);
    stream_.stage_depth(slot, *out.depth, depth_rect(camera, options, reach.rect));
}

CompositeCounts Compositor::draw_staged(int slot, const Camera& camera, const Environment& environment,
                                        RenderTarget& target, StepTimer& timer, const CompositeOptions& options) {
    return compose(nullptr, slot, camera, environment, target, timer, options);
}

void Compositor::object_shadow_reach(const Camera& camera, const Environment& environment,
                                     const CompositeOptions& options, const DepthImage* depth,
                                     ShadowReach& reach) const {
    reach.rects.clear();
    reach.rect = {};
    // As begin() and ObjectShadowMap::update() decide it: shadows on, the sun
    // above the horizon, objects or the vehicle to cast them, the sun's light
    // painted. The vehicle's box is where it will be placed (bounds_at), as
    // this may run before begin() places it.
    const glm::vec3 sun = glm::length(environment.sun_dir) > 0 ? glm::normalize(environment.sun_dir) : glm::vec3(0, 1, 0);
    if (!environment.shadows || !(sun.y > 0) || environment.baked) return;
    // The pixels each object's shadow can reach, down to the lowest terrain:
    // one rectangle per caster, not their bounding rectangle, as the pass
    // costs llvmpipe per pixel it covers (whether a shadow falls there or
    // not) and the scene's objects lie far apart.
    // Each reach goes down to the lowest surface under it rather than to the
    // lowest terrain (a hill's objects shade that hill, not the sea floor):
    // the reach down to a floor holds every point the shadow falls on, so
    // the lowest sample under it (or the water level above that) is a
    // floor again, twice over.
    // Each caster grown by two texels of its shadow map, as the map's
    // filtered lookup darkens up to a texel past the caster's outline.
    std::vector<ShadowCaster> casters;
    std::vector<PixelRect> rects;
    const auto add = [&](std::span<const glm::vec3> points, float texel) {
        WorldBox caster{glm::vec3(std::numeric_limits<float>::max()), glm::vec3(-std::numeric_limits<float>::max())};
        for (const glm::vec3& p : points) {
            caster.lo = glm::min(caster.lo, p - glm::vec3(2.0f * texel));
            caster.hi = glm::max(caster.hi, p + glm::vec3(2.0f * texel));
        }
        float floor = terrain_min_;
        WorldBox box = ObjectShadowMap::reach({caster}, sun, floor).front();
        for (int pass = 0; pass < 2; ++pass) {
            floor = floor_under(box);
            if (environment.water) floor = std::max(floor, environment.water_level);
            box = ObjectShadowMap::reach({caster}, sun, floor).front();
        }
        casters.push_back({points, 2.0f * texel});
        rects.push_back(screen_rect(std::span<const WorldBox>(&box, 1), camera));
    };
    for (const std::vector<glm::vec3>& caster : objects_.casters()) add(caster, object_texel_);
    std::array<glm::vec3, 8> vehicle;
    if (options.vehicle) {
        const WorldBox box = vehicle_.bounds_at(options.vehicle->x, options.vehicle->z, options.vehicle->heading);
        for (int c = 0; c < 8; ++c)
            vehicle[std::size_t(c)] = {c & 1 ? box.hi.x : box.lo.x, c & 2 ? box.hi.y : box.lo.y, c & 4 ? box.hi.z : box.lo.z};
        add(vehicle, ObjectShadowMap::texel_bound({box}, ObjectShadowMap::kVehicleSize));
    }
    // Within those rectangles, with the ray caster's depth at hand, only the
    // pixels whose points lie under a caster from the sun: the shadows'
    // pixels and a thin margin, where the rectangles (a house's reaches
    // down to the lowest sample of the blocks under it) held hundreds of
    // thousands of pixels that no shadow reaches.
    SnapGrid grid = snap_;
    grid.bounds = &snap_bounds_;
    reach.rects = depth ? shadow_pixels(*depth, camera, grid, sun, casters, rects) : disjoint_cover(rects);
    for (const PixelRect& r : reach.rects) reach.rect = bounding_union(reach.rect, r);
}

float Compositor::floor_under(const WorldBox& box) const {
    // The samples whose nearest-sample or bilinear surface reaches into the
    // box's footprint (a cell of margin), by blocks of kFloorBlock samples;
    // a cell lower still for the window depth's rounding.
    const float cell = terrain_.h_scale();
    const auto block = [&](float v, int blocks) {
        return std::clamp(int(std::floor(v / cell)) / kFloorBlock, 0, blocks - 1);
    };
    const int c0 = block(box.lo.x - cell, block_cols_), c1 = block(box.hi.x + cell, block_cols_);
    const int r0 = block(box.lo.z - cell, block_rows_), r1 = block(box.hi.z + cell, block_rows_);
    float lowest = std::numeric_limits<float>::max();
    for (int r = r0; r <= r1; ++r)
        for (int c = c0; c <= c1; ++c) lowest = std::min(lowest, block_min_[std::size_t(r) * std::size_t(block_cols_) + std::size_t(c)]);
    return std::max(terrain_min_, lowest - cell);
}

PixelRect Compositor::depth_rect(const Camera& camera, const Environment& environment,
                                 const CompositeOptions& options) const {
    ShadowReach reach;
    object_shadow_reach(camera, environment, options, nullptr, reach);
    return depth_rect(camera, options, reach.rect);
}

PixelRect Compositor::depth_rect(const Camera& camera, const CompositeOptions& options,
                                 const PixelRect& shadow_rect) const {
    if (options.full_depth) return {0, 0, camera.width, camera.height};
    PixelRect r = objects_.screen_rect(camera);
    if (options.vehicle) {
        const WorldBox box = vehicle_.bounds_at(options.vehicle->x, options.vehicle->z, options.vehicle->heading);
        r = bounding_union(r, screen_rect(std::span<const WorldBox>(&box, 1), camera));
    }
    return bounding_union(r, shadow_rect);
}

CompositeCounts Compositor::compose(const MethodOutput* out, int slot, const Camera& camera,
                                    const Environment& environment, RenderTarget& target, StepTimer& timer,
                                    const CompositeOptions& options) {
    const bool images = !out || out->kind == MethodOutputKind::Images;
    if (!images) {
        if (out->kind == MethodOutputKind::Resident) prepare(out->surface); // uploads are not part of a frame
    }
    // An image composite is drawn offscreen: a window's is then blitted to
    // it. Two targets in turn, so that loading frame N+1 does not wait for GL
    // to finish drawing and blitting frame N from the same textures (a
    // software GL such as llvmpipe rasterises frame N while N+1 is loaded).
    RenderTarget* into = &target;
    if (images && !target.offscreen()) {
        std::unique_ptr<RenderTarget>& next = images_[next_image_];
        next_image_ = (next_image_ + 1) % int(images_.size());
        if (!next || next->width() != camera.width || next->height() != camera.height)
            next = std::make_unique<RenderTarget>(camera.width, camera.height);
        into = next.get();
    }
    if (out && out->kind == MethodOutputKind::Mesh && out->tile_imagery) {
        timer.begin_gl("imagery_tiles");
        tiled_imagery_.update(*out->tile_imagery);
        timer.end_gl();
        frame_.set_tile_imagery(tiled_imagery_.uniform(), tiled_imagery_.size_uniform());
    } else {
        frame_.set_tile_imagery(glm::vec4(0.0f), glm::vec4(0.0f));
    }
    begin(camera, environment, *into, timer, options);
    CompositeCounts counts;
    if (images) {
        // The shadows' reach, worked out once for the frame: for its depth
        // load and its pass.
        const ShadowReach& reach = out ? drawn_reach_ : staged_reach_[std::size_t(slot)];
        if (out && options.objects) {
            const auto t0 = std::chrono::steady_clock::now();
            object_shadow_reach(camera, environment, options, out->depth, drawn_reach_);
            timer.cpu_step_since("shadow_reach", t0);
        }
        draw_images(out, slot, camera, reach, *into, timer, options);
        if (options.objects && (object_shadow_.active() || vehicle_shadow_.active()) && !reach.rects.empty()) {
            timer.begin_gl("object_shadows");
            object_shadow_pass_.draw(*into, camera, reach.rects);
            timer.end_gl();
        }
    } else {
        timer.begin_gl("sky");
        glClearDepth(1.0);
        glClear(GL_DEPTH_BUFFER_BIT);
        sky_.draw();
        timer.end_gl();
        if (options.wireframe) glPolygonMode(GL_FRONT_AND_BACK, GL_LINE);
        frame_.set_terrain_pass(true, environment.baked);
        counts.terrain_primitives = draw_surface(*out, camera, timer, counts);
        frame_.set_terrain_pass(false, false);
        glPolygonMode(GL_FRONT_AND_BACK, GL_FILL);
        if (environment.water) {
            timer.begin_gl("water");
            water_.draw(environment, camera.eye.y);
            timer.end_gl();
        }
    }

    if (!images || options.objects) {
        // The objects over whatever depth the terrain left: Szenberg's composite.
        into->bind();
        frame_.bind();
        depth_test_on();
        timer.begin_gl("objects");
        counts.object_triangles = objects_.draw();
        if (options.vehicle) counts.object_triangles += vehicle_.draw();
        timer.end_gl();
    }
    if (into != &target) {
        timer.begin_gl("blit");
        into->blit_color_to(target);
        timer.end_gl();
        target.bind();
    }
    return counts;
}

void Compositor::draw_images(const MethodOutput* out, int slot, const Camera& camera, const ShadowReach& reach,
                             RenderTarget& into, StepTimer& timer, const CompositeOptions& options) {
    // Staged now (draw()), or earlier on another thread (draw_staged()).
    if (out) slot = acquire_slot(camera);
    timer.begin_gl("color_upload");
    if (out) stream_.stage_color(slot, *out->color);
    stream_.load_color(slot, into);
    timer.end_gl();
    if (!options.objects) return;
    timer.begin_gl("depth_upload");
    if (out) stream_.stage_depth(slot, *out->depth, depth_rect(camera, options, reach.rect));
    stream_.load_depth(slot, into);
    timer.end_gl();
}

long long Compositor::draw_surface(const MethodOutput& out, const Camera& camera, StepTimer& timer,
                                   CompositeCounts& counts) {
    if (out.kind == MethodOutputKind::Mesh) {
        if (!out.mesh) throw Error("compositor", "a mesh method produced no mesh");
        const auto t0 = std::chrono::steady_clock::now();
        streamed_.upload(*out.mesh);
        timer.cpu_step_since("upload", t0);
        timer.begin_gl("terrain");
        const long long n = streamed_.draw();
        timer.end_gl();
        return n;
    }
    timer.begin_gl("terrain");
    long long n = 0;
    if (out.surface == ResidentSurface::Mesh) {
        const TerrainMesh::DrawStats s = mesh_->draw(camera.projection_matrix() * camera.view_matrix());
        counts.chunks_total = s.chunks_total;
        counts.chunks_drawn = s.chunks_drawn;
        n = s.triangles;
    } else {
        n = blocks_->draw(block_method(out.surface));
    }
    timer.end_gl();
    return n;
}

} // namespace overflight::gl
