// Based on: Szenberg et al. 1997 sec. 3, 5 (Fig. 5) and 7 (Tables 1 and 2);
// CMSC 23700 hovercraft project sec. 3-4.
#include "gl/Compositor.h"

#include "core/Error.h"

#include <glm/geometric.hpp>

#include <chrono>

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
    objects_.set_scene(scene, terrain);
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
    if (!shadow_valid_ || shadow_.sun_dir != sun) {
        const auto t0 = std::chrono::steady_clock::now();
        sweep_shadow_ceiling(terrain_, sun, shadow_);
        shadow_texture_.upload(shadow_, terrain_);
        shadow_valid_ = true;
        timer.cpu_step_since("shadow_sweep", t0);
    }
    shadow_texture_.bind();
    return shadow_texture_.uniform();
}

void Compositor::begin(const Camera& camera, const Environment& environment, const RenderTarget& target,
                       StepTimer& timer) {
    camera.validate();
    if (camera.width != target.width() || camera.height != target.height())
        throw Error("camera", "image size differs from the render target");
    const glm::vec4 shadow = terrain_shadow(environment, timer);
    frame_.set_shadow(shadow);
    imagery_texture_.bind();
    frame_.set_imagery(imagery_texture_.uniform());
    frame_.update(camera, environment, terrain_);
    object_shadow_.update(shadow.x > 0, glm::vec3(frame_.block().sun_dir), objects_, frame_.block());
    object_shadow_.bind();
    frame_.bind();
    target.bind();
    depth_test_on();
}

CompositeCounts Compositor::draw(const MethodOutput& out, const Camera& camera, const Environment& environment,
                                 RenderTarget& target, StepTimer& timer, const CompositeOptions& options) {
    if (out.kind == MethodOutputKind::Resident) prepare(out.surface); // uploads are not part of a frame
    if (out.kind == MethodOutputKind::Mesh && out.tile_imagery) {
        timer.begin_gl("imagery_tiles");
        tiled_imagery_.update(*out.tile_imagery);
        timer.end_gl();
        frame_.set_tile_imagery(tiled_imagery_.uniform(), tiled_imagery_.size_uniform());
    } else {
        frame_.set_tile_imagery(glm::vec4(0.0f), glm::vec4(0.0f));
    }
    begin(camera, environment, target, timer);
    CompositeCounts counts;
    if (out.kind == MethodOutputKind::Images) {
        draw_images(out, camera, target, timer, options);
        if (!options.objects) return counts;
        if (object_shadow_.active() && !environment.baked) {
            // The pixels an object's shadow can reach, down to the lowest terrain.
            const PixelRect rect = screen_rect(
                ObjectShadowMap::reach(objects_.bounds(), glm::vec3(frame_.block().sun_dir), terrain_.min_height()), camera);
            timer.begin_gl("object_shadows");
            object_shadow_pass_.draw(*out.depth, camera, rect);
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
        counts.terrain_primitives = draw_surface(out, camera, timer, counts);
        frame_.set_terrain_pass(false, false);
        glPolygonMode(GL_FRONT_AND_BACK, GL_FILL);
        if (environment.water) {
            timer.begin_gl("water");
            water_.draw(environment, camera.eye.y);
            timer.end_gl();
        }
    }

    // The objects over whatever depth the terrain left: Szenberg's composite.
    target.bind();
    frame_.bind();
    depth_test_on();
    timer.begin_gl("objects");
    counts.object_triangles = objects_.draw();
    if (options.vehicle)
        counts.object_triangles += vehicle_.draw(options.vehicle->x, options.vehicle->z, options.vehicle->heading);
    timer.end_gl();
    return counts;
}

void Compositor::draw_images(const MethodOutput& out, const Camera& camera, RenderTarget& target, StepTimer& timer,
                             const CompositeOptions& options) {
    if (!out.color || !out.depth) throw Error("compositor", "an image method produced no color or depth");
    if (target.offscreen()) {
        timer.begin_gl("color_upload");
        target.upload_color(*out.color);
        timer.end_gl();
        if (!options.objects) return;
        // Objects only test depth inside their screen rectangle; the whole
        // buffer is loaded when it is read back or a vehicle can be anywhere.
        timer.begin_gl("depth_upload");
        const bool full = options.full_depth || options.vehicle;
        target.upload_depth(*out.depth, full ? std::nullopt : std::optional<PixelRect>(objects_.screen_rect(camera)));
        timer.end_gl();
        return;
    }
    if (!images_ || images_->width() != camera.width || images_->height() != camera.height)
        images_ = std::make_unique<RenderTarget>(camera.width, camera.height);
    timer.begin_gl("color_upload");
    images_->upload_color(*out.color);
    timer.end_gl();
    timer.begin_gl("depth_upload");
    images_->upload_depth(*out.depth);
    timer.end_gl();
    timer.begin_gl("composite");
    target.draw_from(*images_);
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
