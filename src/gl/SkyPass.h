#pragma once
// The sky behind every terrain method: a full-screen background pass whose
// color is a vertical gradient by the elevation of each pixel's view ray,
//     s = max(dir.y / |dir|, 0),   sky = mix(sky_horizon, sky_zenith, s),
// with dir the camera ray of DESIGN sec. 2 through the pixel centre. It writes
// no depth, so the sky keeps window depth 1.0 (nothing hit); with the
// atmosphere on, the sky of core/AerialPerspective.h (air_sky()). The ray
// caster paints its sky pixels with the same formula so both images agree.
//
// Based on: the hovercraft handout (CMSC 23700 project 2a, skybox) and DESIGN sec. 2 (rays).
#include "gl/GlProgram.h"

namespace overflight::gl {

// The vertex shader of a full-screen pass: one triangle covering the target
// at window depth 1 (three vertices, no attributes).
extern const char* const kFullScreenVs;

class SkyPass {
public:
    SkyPass();
    // Draws the gradient over the whole bound target (Frame block must be bound).
    void draw() const;

private:
    Program program_;
    VertexArray vao_;
};

} // namespace overflight::gl
