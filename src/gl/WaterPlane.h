#pragma once
// The water surface (core/WaterSurface.h) in the GL methods' frames: one
// full-screen pass after the terrain, before the objects, that intersects
// every pixel's ray with the plane y = level and, where the plane is in
// front of the terrain (depth test on the plane's own gl_FragDepth, which
// it writes, so that objects composite against the water), draws the water
// blended over the terrain behind it: the GLSL twin of core/WaterSurface.h
// term for term (waves, Schlick's Fresnel, Beer-Lambert shallows with the
// path from the depth under the point, glint), with dual-source blending
// (ONE, ONE_MINUS_SRC1_COLOR) for the bottom's weight W per channel.
//
// The reflection is the ray casters' approach rather than a planar
// reflection render: the mirrored ray is marched through the same height
// field, uploaded as a texture of world heights with the terrain's colors
// (bilinear heights, steps from half a cell growing by 4 % each, at most
// 192, up to where the ray rises above the highest sample). Its error
// against the ray casters' exact march: a step can pass over a ridge
// thinner than itself (at 100 cells from the water a step is about 2
// cells), and the hit sample's color is lit by its own normal without the
// terrain's cast shadows.
#include "core/DataSet.h"
#include "core/Terrain.h"
#include "gl/GlProgram.h"

namespace overflight::gl {

class WaterPlane {
public:
    // Keeps a reference to terrain (it must outlive this); uploads nothing
    // until the first draw with water.
    explicit WaterPlane(const Terrain& terrain) : terrain_(terrain) {}
    // Draws env's water (nothing without Environment::water, with the eye
    // at or below the level, or for a terrain wider than the GL's largest
    // texture) into the bound target over the terrain's color and depth.
    // The frame uniforms must be bound.
    void draw(const Environment& env, double eye_y);

private:
    const Terrain& terrain_;
    Program program_;
    VertexArray vao_;
    Texture heights_, colors_;
    bool failed_ = false; // the terrain does not fit in a texture
};

} // namespace overflight::gl
