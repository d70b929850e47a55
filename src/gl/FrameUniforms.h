#pragma once
// The per-frame state every GL program reads (uniform block `Frame`, binding
// 0): the camera's view-projection (DESIGN sec. 2, core Camera matrices), the
// sun, fog and sky of the data set's Environment (or its atmosphere's
// per-frame constants, core/AerialPerspective.h), and the terrain grid.
//
// Based on: Szenberg et al. 1997 sec. 5.1 (the OpenGL camera of the ray
// caster) and the hovercraft handout (CMSC 23700 project 2a: sun lighting, GL_EXP fog, sky).
#include "core/Camera.h"
#include "core/DataSet.h"
#include "gl/GlProgram.h"

#include <glm/mat4x4.hpp>
#include <glm/vec4.hpp>

namespace overflight::gl {

// std140 mirror of the GLSL block in kFrameGlsl (GlProgram.cpp).
struct FrameBlock {
    glm::mat4 view_proj;
    glm::vec4 eye, sun_dir, sun_color, ambient, fog, sky_zenith, sky_horizon;
    glm::vec4 view_axis, view_right, view_up, image, grid;
    glm::vec4 air_beta, air_rayleigh, air_haze;
    glm::vec4 shadow; // ShadowCeilingTexture::uniform(), or 0: no terrain shadows
    glm::vec4 look;   // x: 1 while baked surfaces are drawn, y: 1 while the terrain is (set_terrain_pass)
    glm::vec4 imagery; // ImageryTexture::uniform(), or 0: no imagery finer than the samples
    glm::vec4 underwater;       // x: 1 = the eye is under Environment::water's level, y: that level
    glm::vec4 water_absorption; // rgb: kWaterAbsorption (core/WaterSurface.h)
    glm::vec4 water_deep;       // rgb: water_deep_light()
    glm::vec4 tile_imagery, tile_imagery_size; // TiledImageryTexture::uniform(), size_uniform(); 0: none
};

class FrameUniforms {
public:
    FrameUniforms();
    // Fills the block for one frame. view_proj is computed in double as
    // projection_matrix() * view_matrix() * translate(eye) and rounded once to
    // float; shaders transform (world - eye) with it (clip_of() in kFrameGlsl).
    // The terrain's grid is read at the first update() with it: its samples
    // must not change while this object draws it.
    void update(const Camera& camera, const Environment& env, const Terrain& terrain);
    // The terrain shadows of the next update()s (ShadowCeilingTexture::uniform(), 0 = none).
    void set_shadow(const glm::vec4& shadow) { block_.shadow = shadow; }
    // The imagery of the next update()s (ImageryTexture::uniform(), 0 = none).
    void set_imagery(const glm::vec4& imagery) { block_.imagery = imagery; }
    // The imagery tiles of the next update()s (TiledImageryTexture, 0 = none).
    void set_tile_imagery(const glm::vec4& tiles, const glm::vec4& size) {
        block_.tile_imagery = tiles;
        block_.tile_imagery_size = size;
    }
    // Whether what is drawn next is the terrain, and baked (no sun on it): updates the block.
    void set_terrain_pass(bool terrain, bool baked);
    // Binds the block to uniform binding 0.
    void bind() const;
    const FrameBlock& block() const { return block_; }

private:
    FrameBlock block_{};
    const Terrain* grid_terrain_ = nullptr; // whose grid block_.grid holds
    Buffer ubo_;
};

} // namespace overflight::gl
