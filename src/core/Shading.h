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

// The color shade_by_elevation gives sample (row, col) of a terrain whose
// lowest and highest world heights are min_height and max_height. It reads
// only the 3x3 samples around (row, col) (clamped to t), so a window of a
// larger terrain with one sample of margin, and min/max of the whole, gives
// the whole terrain's colors.
Rgb8 shaded_color(const Terrain& t, int row, int col, float min_height, float max_height, float sea_level);

// Sets t.color(row, j) to shaded_color(t, row, j, ...) for every column j.
void shade_row(Terrain& t, int row, float min_height, float max_height, float sea_level);

// Fills t.colors() with elevation_ramp x (0.35 + 0.65 hillshade). Parallel over rows.
void shade_by_elevation(Terrain& t, float sea_level);
// The same with the ramp spread over [min_height, max_height] rather than the
// terrain's own lowest and highest samples (a window of a larger terrain, or
// a resampled raster coloured by its source's range).
void shade_by_elevation(Terrain& t, float sea_level, float min_height, float max_height);

} // namespace overflight
