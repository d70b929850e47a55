#pragma once
// The per-slice depth vector of the Floating Horizon ray caster.
//
// Based on: Szenberg, Gattass, Carvalho 1997, sec. 5.2, eq. 3-7 and
// Algorithm 2. With slices parallel to the screen (vertical view plane, the
// `shear` camera of DESIGN sec. 2), every pixel painted from slice k lies at
// the same eye-space depth d_k, so its OpenGL window depth
//     depth_k = (f - f n / d_k) / (f - n)              (eq. 7)
// is one number per slice, shared by all columns, computed once per camera.
// Algorithm 2 indexes slices by the distance i itself (unit steps, i = n..f);
// here slice k sits at d_k = first + k * step so the voxel size and the far
// distance need not be integers.
#include "core/Camera.h"

#include <vector>

namespace overflight {

// Fills out[k] = window depth of view depth first + k*step for k < count, for
// the camera's near and far (Camera::window_depth). Reuses out's capacity.
void depth_vector(const Camera& camera, double first, double step, int count, std::vector<float>& out);

} // namespace overflight
