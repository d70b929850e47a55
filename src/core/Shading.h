#pragma once
// Colors for a terrain that comes without a color map: an elevation ramp
// (gdaldem color-relief) multiplied by hill shading (gdaldem hillshade,
// Horn's 3x3 gradient, sun from the north-west at 45 degrees).
#include "core/Terrain.h"

namespace overflight {

// Hill-shade factor in [0,1] at a sample (Horn 1981 gradient; azimuth and
// altitude in degrees, azimuth clockwise from north as in gdaldem).
float hillshade(const Terrain& t, int row, int col, float azimuth_deg = 315.0f, float altitude_deg = 45.0f);

// Elevation ramp: water below `sea_level` (world units), then sand, grass,
// forest, rock and snow spread over [sea_level, max_height].
Rgb8 elevation_ramp(float height, float min_height, float max_height, float sea_level);

// Fills t.colors() with elevation_ramp x (0.35 + 0.65 hillshade). Parallel over rows.
void shade_by_elevation(Terrain& t, float sea_level);

} // namespace overflight
