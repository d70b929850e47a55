// Based on: Szenberg et al. 1997 sec. 5.1 (camera mapping) and DESIGN sec. 2.
#include "gl/FrameUniforms.h"

#include "core/AerialPerspective.h"
#include "core/WaterSurface.h"

#include <glm/ext/matrix_transform.hpp>
#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>

#include <cmath>
#include <cstddef>

namespace overflight::gl {

FrameUniforms::FrameUniforms() : ubo_(make_buffer()) {
    glNamedBufferStorage(ubo_.get(), sizeof(FrameBlock), nullptr, GL_DYNAMIC_STORAGE_BIT);
}

void FrameUniforms::update(const Camera& camera, const Environment& env, const Terrain& terrain) {
    // Eye-relative: shaders project (world - eye), which keeps float precision
    // on large terrains where world coordinates reach tens of kilometres.
    block_.view_proj = glm::mat4(camera.projection_matrix() * camera.view_matrix() *
                                 glm::translate(glm::dmat4(1.0), camera.eye));
    block_.eye = glm::vec4(glm::vec3(camera.eye), 1.0f);
    const glm::vec3 sun = glm::length(env.sun_dir) > 0 ? glm::normalize(env.sun_dir) : glm::vec3(0, 1, 0);
    block_.sun_dir = glm::vec4(sun, 0.0f);
    block_.sun_color = glm::vec4(env.sun_color, 1.0f);
    block_.ambient = glm::vec4(env.ambient, 1.0f);
    block_.fog = glm::vec4(env.fog_color, env.fog_density);
    block_.sky_zenith = glm::vec4(env.sky_zenith, 1.0f);
    block_.sky_horizon = glm::vec4(env.sky_horizon, 1.0f);
    block_.view_axis = glm::vec4(glm::vec3(camera.view_axis()), 0.0f);
    block_.view_right = glm::vec4(glm::vec3(camera.right()), 0.0f);
    block_.view_up = glm::vec4(glm::vec3(camera.view_up()), 0.0f);
    const double fp = camera.focal_px();
    const double shift = camera.projection == Projection::Shear ? fp * std::tan(glm::radians(camera.pitch)) : 0.0;
    block_.image = glm::vec4(float(camera.width), float(camera.height), float(fp), float(shift));
    if (&terrain != grid_terrain_) { // Terrain::min_height() reads every sample: once per terrain
        grid_terrain_ = &terrain;
        block_.grid = glm::vec4(terrain.h_scale(), terrain.min_height(), float(terrain.rows()), float(terrain.cols()));
    }
    if (env.atmosphere) {
        const AerialFrame air = aerial_frame(env, camera.eye.y);
        block_.air_beta = glm::vec4(glm::vec3(air.beta * air.eye_density), float(air.scale_height));
        block_.air_rayleigh = glm::vec4(glm::vec3(air.rayleigh_light), float(air.g));
        block_.air_haze = glm::vec4(glm::vec3(air.haze_light), 1.0f);
    } else {
        block_.air_beta = block_.air_rayleigh = block_.air_haze = glm::vec4(0.0f);
    }
    const bool under = env.water && camera.eye.y < double(env.water_level);
    block_.underwater = glm::vec4(under ? 1.0f : 0.0f, env.water_level, 0.0f, 0.0f);
    block_.water_absorption = glm::vec4(kWaterAbsorption[0], kWaterAbsorption[1], kWaterAbsorption[2], 0.0f);
    block_.water_deep = glm::vec4(water_deep_light(env), 0.0f);
    glNamedBufferSubData(ubo_.get(), 0, sizeof(FrameBlock), &block_);
}

void FrameUniforms::set_terrain_pass(bool terrain, bool baked) {
    const glm::vec4 look(terrain && baked ? 1.0f : 0.0f, terrain ? 1.0f : 0.0f, 0.0f, 0.0f);
    if (block_.look == look) return;
    block_.look = look;
    glNamedBufferSubData(ubo_.get(), GLintptr(offsetof(FrameBlock, look)), sizeof(glm::vec4), &block_.look);
}

void FrameUniforms::bind() const { glBindBufferBase(GL_UNIFORM_BUFFER, 0, ubo_.get()); }

} // namespace overflight::gl
