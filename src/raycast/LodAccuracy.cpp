// Based on: DESIGN sec. 2 (window depth 1.0 = sky).
#include "raycast/LodAccuracy.h"

#include "core/Error.h"

#include <algorithm>
#include <cstdlib>
#include <string>

namespace overflight {

namespace {

bool is_sky(float depth) { return !(depth < 1.0f); }

// Row of the topmost terrain pixel of column `col`, or height when the column is all sky.
int silhouette_row(const DepthImage& img, int col) {
    for (int row = 0; row < img.height; ++row)
        if (!is_sky(img.at(col, row))) return row;
    return img.height;
}

} // namespace

SilhouetteAgreement compare_silhouettes(const DepthImage& test, const DepthImage& reference, int tolerance_rows) {
    if (test.width != reference.width || test.height != reference.height)
        throw Error("silhouette", "images of " + std::to_string(test.width) + "x" + std::to_string(test.height) +
                                      " and " + std::to_string(reference.width) + "x" +
                                      std::to_string(reference.height) + " differ in size");
    if (tolerance_rows < 0) throw Error("silhouette", "tolerance " + std::to_string(tolerance_rows) + " is below 0");
    SilhouetteAgreement a;
    a.pixels = (long long)test.pixels.size();
    for (std::size_t i = 0; i < test.pixels.size(); ++i)
        a.sky_agreeing += is_sky(test.pixels[i]) == is_sky(reference.pixels[i]);
    a.columns = test.width;
    for (int col = 0; col < test.width; ++col) {
        const int t = silhouette_row(test, col), r = silhouette_row(reference, col);
        const bool t_sky = t == test.height, r_sky = r == reference.height;
        if (t_sky || r_sky) {
            a.columns_within += t_sky && r_sky;
            continue;
        }
        const int d = std::abs(t - r);
        a.max_row_difference = std::max(a.max_row_difference, d);
        a.columns_within += d <= tolerance_rows;
    }
    return a;
}

} // namespace overflight
