// Based on: Szenberg et al. 1997 sec. 3, 5, 7; DESIGN sec. 2, 3, 5.
#include "gl/Renderer.h"

#include "core/Error.h"

namespace overflight::gl {

std::optional<TerrainMethod> parse_terrain_method(std::string_view name) {
    if (name == "mesh") return TerrainMethod::Mesh;
    if (name == "points") return TerrainMethod::Points;
    if (name == "top-faces") return TerrainMethod::TopFaces;
    if (name == "front-faces") return TerrainMethod::FrontFaces;
    if (name == "segments") return TerrainMethod::Segments;
    if (name == "blocks") return TerrainMethod::Blocks;
    return std::nullopt;
}

const char* to_string(TerrainMethod m) {
    switch (m) {
    case TerrainMethod::Mesh: return "mesh";
    case TerrainMethod::Points: return "points";
    case TerrainMethod::TopFaces: return "top-faces";
    case TerrainMethod::FrontFaces: return "front-faces";
    case TerrainMethod::Segments: return "segments";
    case TerrainMethod::Blocks: return "blocks";
    }
    return "mesh";
}

namespace {
BlockMethod block_method(TerrainMethod m) {
    switch (m) {
    case TerrainMethod::Points: return BlockMethod::Points;
    case TerrainMethod::TopFaces: return BlockMethod::TopFaces;
    case TerrainMethod::FrontFaces: return BlockMethod::FrontFaces;
    case TerrainMethod::Segments: return BlockMethod::Segments;
    default: return BlockMethod::Blocks;
    }
}
} // namespace

Renderer::Renderer(const DataSet& data) : data_(data) {}

void Renderer::set_scene(const Scene& scene) { objects_.set_scene(scene, data_.terrain); }

void Renderer::begin_composite(const Camera& camera, const RenderTarget& target) {
    camera.validate();
    if (camera.width != target.width() || camera.height != target.height())
        throw Error("camera", "image size differs from the render target");
    clip_ = camera.projection_matrix() * camera.view_matrix();
    frame_.update(camera, data_.environment, data_.terrain);
    frame_.bind();
    target.bind();
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glDepthMask(GL_TRUE);
    glDisable(GL_CULL_FACE);
    glFrontFace(GL_CCW);
}

void Renderer::begin_frame(const Camera& camera, const RenderTarget& target) {
    begin_composite(camera, target);
    glClearDepth(1.0);
    glClear(GL_DEPTH_BUFFER_BIT);
    sky_.draw();
}

void Renderer::prepare(TerrainMethod method) {
    if (method == TerrainMethod::Mesh) {
        if (!mesh_) mesh_ = std::make_unique<TerrainMesh>(data_.terrain);
    } else if (!blocks_) {
        blocks_ = std::make_unique<BlockTerrain>(data_.terrain);
    }
}

TerrainDrawStats Renderer::draw_terrain(TerrainMethod method) {
    prepare(method);
    TerrainDrawStats s;
    if (method == TerrainMethod::Mesh) {
        const TerrainMesh::DrawStats m = mesh_->draw(clip_);
        s.primitives = m.triangles;
        s.chunks_total = m.chunks_total;
        s.chunks_drawn = m.chunks_drawn;
    } else {
        s.primitives = blocks_->draw(block_method(method));
    }
    return s;
}

long long Renderer::draw_mesh(const MeshArrays& mesh) {
    streamed_.upload(mesh);
    return streamed_.draw();
}

long long Renderer::draw_objects() { return objects_.draw(); }

} // namespace overflight::gl
