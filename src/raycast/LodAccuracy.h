#pragma once
// How closely the ray caster's distance LOD (RaycastOptions::lod) keeps the
// exact cast's outline: the two depth images of the same camera are compared
// where they differ most visibly, at the sky. A LOD that samples the
// max-height pyramid mostly raises distant silhouettes (a max bounds every
// sample below it; its coarser slices can still step over a thin ridge), so
// the measure is the sky mask and the topmost terrain row of each column, not
// colors.
//
// Based on: the pyramids of HeightPyramid (max heights, mean colors) and the
// window depth of DESIGN sec. 2 (1.0 = sky, nothing hit).
#include "core/Image.h"

namespace overflight {

struct SilhouetteAgreement {
    long long pixels = 0;          // pixels compared
    long long sky_agreeing = 0;    // sky in both images or terrain in both
    int columns = 0;               // columns compared
    int columns_within = 0;        // of those, silhouettes within `tolerance_rows` (or sky in both)
    int max_row_difference = 0;    // largest silhouette difference of a column with terrain in both
    double sky_share() const { return pixels ? double(sky_agreeing) / double(pixels) : 1.0; }
    double column_share() const { return columns ? double(columns_within) / double(columns) : 1.0; }
};

// The silhouette of a column is its topmost terrain pixel (row 0 = top; depth
// < 1). A column counts as within when both images have terrain in it and
// their silhouette rows differ by at most `tolerance_rows`, or when both are
// sky all the way down. Throws Error("silhouette", ...) when the images differ
// in size or `tolerance_rows` < 0.
SilhouetteAgreement compare_silhouettes(const DepthImage& test, const DepthImage& reference, int tolerance_rows = 1);

} // namespace overflight
