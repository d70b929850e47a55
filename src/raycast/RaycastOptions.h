#pragma once
// Options and statistics shared by the terrain ray casters (FloatingHorizon,
// FloatingHorizonLiteral, RayMarcher).
#include <string>

namespace overflight {

// DESIGN sec. 3. Colors are the nearest sample's in both models.
enum class SurfaceModel { Blocks, Bilinear };

// How the Floating Horizon handles the `tilt` camera, whose pixel columns are
// not vertical planes (DESIGN sec. 2):
//   Exact  - cast a sheared image through vertical planes that cover the tilted
//            frustum, with one row per tilted image row (its exact ray slope),
//            and reproject each tilted pixel onto the nearest cast plane
//            (planes at twice the pixel density: at most a quarter pixel
//            sideways, exact vertically);
//   Guedes - Guedes' per-row ray slopes dz[row] and incremental d-buffer
//            (Guedes, "Integrating Polygonal Objects on Voxel Based Terrain
//            Models", Algorithm 1): each column is one vertical plane.
enum class TiltMethod { Exact, Guedes };

// The instruction set the Floating Horizon's block cast is compiled for. Auto
// picks X86_64_v4 (16 columns in lockstep for the shear camera's cast) or
// else X86_64_v3 where the CPU has it; all paint the same pixels (the others
// are for tests and measurements, when cast_kernel_available()).
enum class CastKernel { Auto, Portable, X86_64_v3, X86_64_v4 };

// The kernel of the shear camera's resolve and imagery drape
// (raycast/ShearResolve.h, ShearDrape.h; all give the same bits). Auto picks
// the fastest the CPU runs; the others are for tests and measurements, when
// resolve_kernel_available().
enum class ResolveKernel { Auto, Portable, Avx2, Avx2Loads, Avx2Window, Avx512, Simd128 };

const char* to_string(SurfaceModel s);
const char* to_string(TiltMethod t);
// Parse a name ("blocks", "bilinear", "exact", "guedes"); throw Error(option, ...) otherwise.
SurfaceModel parse_surface_model(const std::string& name, const std::string& option = "--surface");
TiltMethod parse_tilt_method(const std::string& name, const std::string& option = "--tilt-method");

struct RaycastOptions {
    SurfaceModel surface = SurfaceModel::Blocks;
    TiltMethod tilt = TiltMethod::Exact;
    // Distance LOD: past the distance where one pixel spans lod_pixels * 2^L
    // cells, sample level L of the max-height / mean-color pyramids with a step
    // of 2^L cells. Off by default (the exact mode).
    bool lod = false;
    double lod_pixels = 0.5;
    // Near refinement: where one cell spans more than this many pixels, slices
    // come closer than one cell (down to 1/8 cell) so that the point samples of
    // Algorithm 1 still find the blocks' front faces and ridges within about a
    // pixel. 0 turns it off (every slice one cell apart, as in the paper).
    double near_step_pixels = 0.0;
    // Skip runs of slices whose every sample the max-height pyramid proves to
    // stay below the current horizon (one-cell slices, `blocks` surface). Exact:
    // such runs paint nothing; off only to measure or test that.
    bool skip_runs = true;
    CastKernel kernel = CastKernel::Auto;
    ResolveKernel resolve = ResolveKernel::Auto;
};

// What one frame cost, for --stats and `overflight bench`.
struct RaycastStats {
    double ms_setup = 0;    // per-frame tables: slices, rows, columns, depth vector
    double ms_cast = 0;     // floating horizon over all columns
    double ms_resolve = 0;  // fog, sky, depth (tilt: and reprojection) to the image
    // Shear fuses both per block: the step's wall time is split in proportion
    // to the thread time each took.
    double ms_total = 0;
    long long samples = 0;         // columns x slices up to far (the size of the problem)
    long long samples_visited = 0; // height samples actually read (clipping, early exit and skipped runs spare the rest)
    long long pixels_painted = 0;  // terrain pixels
    int columns = 0;               // vertical planes cast (W for shear; more for tilt exact)
    int slices = 0;                // slices from near to far
    int fallback_pixels = 0;       // tilt pixels past the vertical, traced by the ray marcher
};

} // namespace overflight
