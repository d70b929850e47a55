#pragma once
// Zamri's fidelity measure for the quadtree renderer, computed on the CPU so
// it needs no GPU: render the depth of the simplified mesh and of the
// full-resolution mesh with the shared camera, and count the terrain pixels
// whose view depth agrees within a tolerance (Zamri, "Results":
// 95.34 % of the full resolution data kept).
//
// Based on: Zamri ("Results"); the full mesh is DESIGN sec. 3
// `mesh` (two triangles per cell, diagonals alternating as in the binary
// triangle tree); depth is DESIGN sec. 2 window depth.
#include "core/Camera.h"
#include "core/Image.h"
#include "core/MeshArrays.h"
#include "core/Terrain.h"

#include <vector>

namespace overflight {

// Every sample and two triangles per grid cell (the reference of the LOD
// renderers). Colors and normals are left empty: only depth is compared.
MeshArrays full_resolution_mesh(const Terrain& terrain);

// Z-buffer rasterisation of a triangle mesh into OpenGL window depth with
// the camera's matrices (pixel centres as in DESIGN sec. 2, near-plane
// clipping, no back-face culling); 1.0 where nothing is hit. A reference
// for tests and benchmarks, not a renderer.
DepthImage rasterize_depth(const MeshArrays& mesh, const Camera& camera);

struct DepthAgreement {
    long long terrain_pixels = 0; // pixels the reference hits
    long long agreeing = 0;       // of those, |d - d_ref| <= tolerance * d_ref in view depth
    long long coverage_mismatch = 0; // terrain in one image, sky in the other
    double share() const { return terrain_pixels ? double(agreeing) / double(terrain_pixels) : 1.0; }
};

// Compares view depths (not window depths, which are compressed near 1).
DepthAgreement compare_depth(const DepthImage& test, const DepthImage& reference, const Camera& camera,
                             double tolerance = 0.03);

// Screen-space geometric error of a simplified terrain mesh (the quantity the
// quadtree's --error bounds): for every sample of `terrain` inside the view
// frustum and covered by `mesh` in XZ, the distance in pixels between the
// projection of the sample and the projection of the mesh point straight
// above or below it (same X, Z). Occlusion is ignored: it is the geometric
// error, not an image difference. `mesh` vertices must lie on samples (X =
// hs * col, Z = hs * row), as the LOD meshes' do.
struct ScreenError {
    long long samples = 0;  // samples inside the frustum and under the mesh
    double max_px = 0.0;
    double mean_px = 0.0;
    double p99_px = 0.0;    // 99th percentile
};
ScreenError screen_space_error(const MeshArrays& mesh, const Terrain& terrain, const Camera& camera);

} // namespace overflight
