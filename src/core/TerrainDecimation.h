#pragma once
// A terrain made smaller by keeping every f-th sample, for a consumer that
// holds at most a given number of samples per side (the web page of
// `overflight web`: a browser tab's memory and a download).
//
// Heights are point-sampled rather than averaged, so that every kept sample
// keeps its world position and height (DESIGN sec. 1 with h_scale * f): a
// position given in world units (the vehicle's start, an object) lands on the
// same ground as on the full terrain, within the coarser grid's cells. Colors
// are the mean of the f x f samples around each kept one (a box filter), so
// that the coarser picture does not alias.
#include "core/Terrain.h"

#include <string>

namespace overflight {

// The smallest whole factor f such that keeping every f-th sample leaves at
// most `max_size` samples on each side of a rows x cols grid: 1 when it
// already fits. max_size must be at least 2.
int decimation_factor(int rows, int cols, int max_size);

// Why a rows x cols grid cannot be decimated by `factor` (its shorter side
// would keep fewer than 2 samples), or an empty string when it can.
std::string decimation_problem(int rows, int cols, int factor);

// Samples (i f, j f) of `t` for i < (rows - 1) / f + 1, j < (cols - 1) / f + 1,
// with h_scale * f, the same v_scale and y_offset; the last (rows - 1) % f
// rows and (cols - 1) % f columns, which fall between kept samples, are
// dropped. The imagery finer than the samples is not carried over (the
// colors hold it averaged). factor 1 returns a copy. Throws
// Error("terrain", decimation_problem(...)) when that is not empty.
Terrain decimate_terrain(const Terrain& t, int factor);

} // namespace overflight
