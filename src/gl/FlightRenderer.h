#pragma once
// One frame of `fly`, in the window or in a headless replay, whatever the
// terrain method: the Frame uniforms for the camera and the toggled
// environment; depth cleared and the sky drawn unless the method paints every
// pixel itself (the ray caster); the method's terrain; then the objects of the
// data set (map + --scene) and the hovercraft with the Z-buffer, so that they
// are composited by depth over any terrain (Szenberg et al. 1997 sec. 5,
// Fig. 5). Every step is timed through a FlightStepTimer.
//
// Based on: Szenberg et al. 1997 sec. 5 and 7 (Table 1 steps), seed 003
// sec. 3-4 (vehicle, sun, fog, sky).
#include "core/Camera.h"
#include "core/DataSet.h"
#include "gl/FlightMethod.h"
#include "gl/FlightTimer.h"
#include "gl/FlightVehicle.h"
#include "gl/FrameUniforms.h"
#include "gl/ObjectRenderer.h"
#include "gl/RenderTarget.h"
#include "gl/SkyPass.h"

#include <optional>

namespace overflight::gl {

// Where the hovercraft is, if one is drawn (DESIGN sec. 1 heading).
struct VehiclePose {
    double x = 0, z = 0, heading = 0;
};

struct FlightFrameCounts {
    long long terrain_triangles = 0;
    long long object_triangles = 0; // scene objects and the vehicle
};

class FlightRenderer {
public:
    // Uploads data.scene (Error(path, ...) for a bad model file). `data` must
    // outlive the renderer; a GL context must be current.
    explicit FlightRenderer(const DataSet& data);

    // Draws one frame of `method` for `camera` (validated; its size must be
    // the target's) into `target`, which is bound here. The vehicle, when
    // given, is drawn and is the focus of the method's level of detail.
    FlightFrameCounts draw(FlightMethod& method, const Camera& camera, const Environment& env,
                           const RenderTarget& target, FlightStepTimer& timer,
                           const std::optional<VehiclePose>& vehicle, bool wireframe);

private:
    const DataSet& data_;
    FrameUniforms frame_;
    SkyPass sky_;
    ObjectRenderer objects_;
    FlightVehicle vehicle_;
};

} // namespace overflight::gl
