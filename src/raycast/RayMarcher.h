#pragma once
// The reference terrain renderer: one ray per pixel, marched through the
// height field with no coherence between pixels, so that the Floating Horizon
// can be checked against it (DESIGN sec. 8).
//
// Based on: Szenberg 1997 sec. 4 (the plain ray casting the Floating Horizon
// optimises), with rays built independently from Camera::ray: each pixel centre
// is unprojected through the inverse of the OpenGL projection * view matrices
// (near and far planes), and depth is the hit point pushed back through the same
// matrices, exactly as GL would rasterise a surface there. Shear and tilt
// cameras are therefore handled alike.
//
// Surfaces (DESIGN sec. 3), both limited to X in [0, width], Z in [0, depth]:
//   blocks   - exact intersection with flat-topped columns centred on the
//              samples (Amanatides-Woo traversal of the cells around samples,
//              raycast/CellTraversal.h); with a max-height pyramid, rising
//              segments jump over the blocks they pass above, landing on the
//              cells and parameters the plain traversal reaches (same hits,
//              bit for bit);
//   bilinear - march with steps of a quarter cell, then bisection.
// The color is the nearest sample's; fog and sky follow Atmosphere.h.
#include "core/AerialPerspective.h"
#include "core/Camera.h"
#include "core/DataSet.h"
#include "core/Image.h"
#include "core/Terrain.h"
#include "raycast/HeightPyramid.h"
#include "raycast/RaycastOptions.h"

#include "core/ImageryPyramid.h"

#include <glm/mat4x4.hpp>

#include <vector>

namespace overflight {

class RayMarcher {
public:
    // Keeps references: terrain and env must outlive the marcher.
    RayMarcher(const Terrain& terrain, const Environment& env) : terrain_(terrain), env_(env) {}
    // Paints `colors` (one per sample, e.g. sun-lit; must outlive the
    // marcher) instead of the terrain's own; null: the terrain's.
    void set_colors(const std::vector<Rgb8>* colors) { colors_ = colors; }
    // The terrain's max-height pyramid (HeightPyramid of this terrain; must
    // outlive its use) for the `blocks` surface to skip with; null: every cell.
    void set_pyramid(const HeightPyramid* pyramid) { pyramid_ = pyramid; }
    // Imagery finer than the samples (null: none): the painted colors are
    // then each sample's light (128 is 1), times the imagery's nearest texel
    // at the hit point on the mip level of the pixel's footprint
    // (raycast/ImageryTexels.h).
    void set_imagery(const ImageryPyramid* imagery) { imagery_ = imagery; }

    // Renders every pixel (parallel over rows). Resizes the images to the camera.
    void render(const Camera& camera, SurfaceModel surface, ColorImage& color, DepthImage& depth) const;

    // Per-camera data for shade_pixel.
    struct Frame {
        glm::dmat4 view_projection;
        glm::dmat4 inverse_view_projection;
        AerialFrame air; // the environment's atmosphere at the eye (Environment::atmosphere)
    };
    Frame frame(const Camera& camera) const;

    struct Hit {
        bool hit = false;
        glm::dvec3 point{0.0};
        Rgb8 surface{};   // the sample's color, before fog
    };
    // First intersection of the segment a -> b (world) with the surface.
    Hit intersect(const glm::dvec3& a, const glm::dvec3& b, SurfaceModel surface) const;

    // Color (fog or sky applied) and window depth (1 for sky) of pixel (col, row).
    void shade_pixel(const Camera& camera, const Frame& frame, SurfaceModel surface, int col, int row, Rgb8& color,
                     float& depth) const;

private:
    Hit intersect_blocks(const glm::dvec3& a, const glm::dvec3& b) const;
    Hit intersect_bilinear(const glm::dvec3& a, const glm::dvec3& b) const;
    Rgb8 color_at(int row, int col) const {
        return colors_ ? (*colors_)[terrain_.index(row, col)] : terrain_.color(row, col);
    }
    // The world height of the pyramid's level L block holding cell (row,
    // col), as Terrain::sample_height converts its raw value (so that it
    // bounds every sample_height in the block).
    double block_height(int L, int row, int col) const {
        const HeightPyramid::Level& l = pyramid_->level(L);
        const std::uint16_t raw = l.heights[std::size_t(row >> L) * std::size_t(l.cols) + std::size_t(col >> L)];
        return double(terrain_.v_scale() * float(raw) + terrain_.y_offset());
    }

    const Terrain& terrain_;
    const Environment& env_;
    const std::vector<Rgb8>* colors_ = nullptr;
    const HeightPyramid* pyramid_ = nullptr;
    const ImageryPyramid* imagery_ = nullptr;
};

} // namespace overflight
