#pragma once
// What the `fly` window asks of a terrain method (mesh, voxel, roam,
// quadtree): paint the terrain's color and OpenGL window depth (DESIGN sec. 2;
// 1.0 where nothing was hit) for the shared camera into the bound target, so
// that the objects drawn afterwards with the Z-buffer land on the same pixels
// whichever method drew the ground (Szenberg et al. 1997 sec. 5, Fig. 5).
//
// Based on: Szenberg et al. 1997 sec. 5 (composite of any terrain image with
// Z-buffered objects) and seed 003 sec. 3.1 (+ / _ level of detail by sqrt 2).
#include "core/Camera.h"
#include "core/DataSet.h"
#include "gl/FlightTimer.h"
#include "gl/RenderTarget.h"

#include <glm/vec2.hpp>

#include <functional>
#include <memory>
#include <optional>
#include <string>

namespace overflight::gl {

// One frame as a method sees it. When draw() is called the target is bound
// with its viewport, the Frame uniforms (FrameUniforms) hold this camera and
// environment and are bound, and, unless the method covers_frame(), depth is
// cleared to 1.0 and the sky is drawn.
struct FlightView {
    const Camera& camera;            // width/height = the target's size
    const Environment& environment;  // with the fog / lighting toggles applied
    const RenderTarget& target;      // a window's default framebuffer or an offscreen target
    FlightStepTimer& timer;          // the method reports its steps here
    std::optional<glm::dvec2> focus; // world (x, z) of the vehicle, if one is flying
    bool wireframe = false;
};

// A terrain method of the window. Methods are created after the GL context
// exists; they must not allocate per frame in steady state.
class FlightMethod {
public:
    virtual ~FlightMethod() = default;
    virtual const char* name() const = 0;
    // True when draw() writes every pixel's color and depth itself (the ray
    // caster paints its own sky); false to get a cleared depth and the sky first.
    virtual bool covers_frame() const { return false; }
    // Draws the terrain of one frame; returns the terrain triangles drawn (0
    // for methods without any). Steps are timed through view.timer.
    virtual long long draw(const FlightView& view) = 0;
    // Level of detail x factor (seed 003 "+": factor sqrt 2; "_": 1/sqrt 2):
    // a larger triangle budget or a smaller screen error. Methods without a
    // level of detail ignore it.
    virtual void scale_detail(double /*factor*/) {}
    // The current level of detail for the HUD, e.g. "budget 65536" ("" if none).
    virtual std::string detail() const { return {}; }
};

// Builds the method named `name` for `data` in the current context; returns
// nullptr for a name it does not know. Supplied by the caller (apps/cmd_fly.cpp)
// so the command decides which methods are offered.
using FlightMethodFactory = std::function<std::unique_ptr<FlightMethod>(const std::string& name, const DataSet& data)>;

} // namespace overflight::gl
