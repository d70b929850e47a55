#pragma once
// The hovercraft data set (CMSC 23700 project 2a, sec. 6; DESIGN sec. 4): a directory
// holding `map` (TOML, MapFile.h), `hf.pgm` (16-bit PGM height field, side
// 2^N+1 by convention) and `color.ppm` (one pixel per grid cell).
//
// Based on: CMSC 23700 project 2a, sec. 6.1-6.3.
#include "core/DataSet.h"

#include <string>

namespace overflight {

// Loads a data set directory: hs = h_scale, vs = v_scale, y0 = the map's
// y_offset (0 unless given, as in the course's data sets). color.ppm
// may have one pixel per grid cell ((rows-1) x (cols-1): each sample takes the
// mean of the up to four cells around it) or one per sample (rows x cols); when
// it is absent the terrain is shaded by elevation. Throws Error(file, problem)
// for a missing map or hf.pgm, a bad map, a bad PGM/PPM, a PPM whose size
// matches neither convention, and Error(map, ...) for scales that give an
// extent or elevations beyond kWorldLimit (core/Terrain.h) or do not fit a
// float, and a [vehicle] start outside the terrain.
DataSet load_hovercraft(const std::string& dir);

// Writes `data` as a data set into `dir` (created if needed): map, hf.pgm
// (maxval 65535) and color.ppm with one pixel per grid cell (the mean of the
// cell's four corner samples). Each file is written atomically.
void save_hovercraft(const std::string& dir, const DataSet& data);

// Color conversions between the per-cell convention of the data set and the
// per-sample colors of Terrain.
ColorImage cell_colors_to_samples(const ColorImage& cells);   // (r-1)x(c-1) -> r x c
ColorImage sample_colors_to_cells(const Terrain& terrain);    // r x c -> (r-1)x(c-1)

} // namespace overflight
