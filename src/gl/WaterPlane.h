#pragma once
// The water surface (core/WaterSurface.h) in the GL methods' frames: one
// full-screen pass after the terrain, before the objects, that intersects
// every pixel's ray with the plane y = level and, where the plane is in
// front of the terrain (depth test on the plane's own gl_FragDepth, which
// it writes, so that objects composite against the water), draws the water
// blended over the terrain behind it; with the eye under the water, the
// surface seen from below, opaque (the extinction of everything else is
// fogged()'s, kFrameGlsl): the GLSL twin of core/WaterSurface.h
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
// terrain's cast shadows. A terrain wider than the GL's largest texture is
// uploaded decimated k times (water_decimation), each texel the highest
// sample around it, so that the mirrored rays stop on a ridge no later than
// through the full heights (at most k - 1 samples early) and the shallows'
// depth is taken k times coarser.
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
    // at the level) into the bound target over the terrain's color and
    // depth. The frame uniforms must be bound.
    void draw(const Environment& env, double eye_y);
    // The largest texture side to use instead of the GL's (> 1; before the
    // first draw): tests of the decimated upload on small terrains.
    void set_max_texture_size(int size) { max_size_ = size; }
    // How many samples apart the uploaded heights are (1 until the first draw).
    int decimation() const { return decimation_; }

private:
    const Terrain& terrain_;
    Program program_;
    VertexArray vao_;
    Texture heights_, colors_;
    int max_size_ = 0, decimation_ = 1;
    float top_ = 0; // Terrain::max_height() (it reads every sample), with the textures
};

// The smallest k such that a terrain of cols x rows samples, decimated to
// every k-th sample plus one texel past the last, fits in max_size texels a side.
int water_decimation(int cols, int rows, int max_size);

} // namespace overflight::gl
