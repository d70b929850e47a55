#pragma once
// The shape shared by the fly methods whose mesh is rebuilt on the CPU every
// frame (roam, quadtree): build the plain arrays (one timed CPU step), stream
// them to GL ("upload"), draw them lit and fogged like the full mesh
// ("terrain"), in wireframe when asked. The LOD code only produces arrays
// (DESIGN sec. 7); this class only uploads and draws them.
#include "core/MeshArrays.h"
#include "gl/FlightMethod.h"
#include "gl/StreamedMesh.h"

namespace overflight::gl {

class StreamedFlightMethod : public FlightMethod {
public:
    long long draw(const FlightView& view) final;

protected:
    // The HUD name of the CPU step ("tessellate", "refine").
    virtual const char* build_step() const = 0;
    // Fills `mesh` for view.camera (and view.focus).
    virtual void build(const FlightView& view, MeshArrays& mesh) = 0;

private:
    MeshArrays mesh_;
    StreamedMesh streamed_;
};

} // namespace overflight::gl
