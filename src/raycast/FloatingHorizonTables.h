#pragma once
// The per-frame tables of the Floating Horizon ray caster: where the slices
// are and what every column shares about each of them, which vertical plane
// each cast column follows and which of its slices lie on the terrain, the
// ray slope of each cast row. Pure functions of the camera, the terrain's
// size and scales and the options (no state), so that each can be checked on
// a hand-sized terrain; outputs go into the caller's vectors, reusing their
// capacity (no allocation per frame once the sizes are stable).
//
// Based on: Szenberg, Gattass, Carvalho, "An Algorithm for the Visualization
// of a Terrain with Objects", SIBGRAPI 1997: Algorithm 1 (the horizon test of
// a sample against the current row's ray), sec. 5.2 (slices parallel to the
// screen: column k steps by the unit step scaled by 1/cos(theta_k), so slice
// i is at the same view depth d_i for every column), eq. 3-7 and Algorithm 2
// (the depth vector). Guedes, "Integrating Polygonal Objects on Voxel Based
// Terrain Models", Algorithm 1 (the pitched camera's per-row ray slopes).
#include "core/Camera.h"
#include "core/Terrain.h"

#include <cstdint>
#include <vector>

namespace overflight {

// The eye in grid units and the view's horizontal axes.
struct ViewAxes {
    double eye_gx = 0, eye_gz = 0; // eye X, Z over h_scale: sample coordinates
    double eye_y = 0;              // eye height, world units
    double fx = 0, fz = 0;         // F, XZ
    double rx = 0, rz = 0;         // R, XZ
};
ViewAxes view_axes(const Camera& camera, double h_scale);

// Where the slices go, from d_first to d_last along F.
struct SlicePlacement {
    double d_first = 0, d_last = 0;
    double h_scale = 1;            // one cell: the step of the papers' slices
    double fp_h = 1;               // pixels per unit of sideways offset at unit depth (the cast's focal length)
    bool lod = false;              // distance LOD (RaycastOptions::lod) ...
    int lod_levels = 0;            // ... over this many pyramid levels
    double lod_pixels = 0.5;       // RaycastOptions::lod_pixels
    double near_step_pixels = 0.0; // RaycastOptions::near_step_pixels
};

struct Slices {
    std::vector<double> d;           // view depth along F of slice k
    std::vector<float> df;           // the same in float (fog distance)
    std::vector<std::uint8_t> level; // pyramid level sampled at slice k (0: the terrain)
    bool uniform = true;             // all one cell apart (even == d.size())
    // The first `even` slices are one cell apart, at d[k] = d[0] + step k and
    // df[k] = float(d[0]) + float(step) float(k), as when uniform (all of them
    // when uniform; the LOD's level-0 part, without near refinement), so that
    // the cast treats them as the papers' slices and the shear resolve may
    // compute their view depth rather than read it.
    int even = 0;
    double step = 0; // h_scale (0 when even is 0)
};

// Slices one cell apart (sec. 5.2: one step of h_scale along F is the
// column's unit step scaled by 1/cos(theta_k)). With LOD the step doubles
// each time a pixel (1/fp_h of the distance) spans twice as many cells; with
// near refinement it shrinks near the eye (down to 1/8 cell) so that a step
// spans at most near_step_pixels pixels.
void place_slices(const SlicePlacement& placement, Slices& out);

// What every column shares about slice k, with 1/d_k folded in so that the
// horizon test of Algorithm 1 needs no division per sample: a sample of raw
// height h at slice k rises above the ray of slope m (per unit of view depth)
// when h a[k] + b[k] > m, i.e. (v_scale h + y_offset - eye_y) / d_k > m.
// smax[k] is the largest such slope of any sample at slices k and beyond
// (max_height: the highest sample, world units), rounded up.
// v_scale and base (y_offset - eye_y) give the same slope for any view
// depth d: (v_scale h + base) / d (FrontFace.h).
struct SliceSlopes {
    std::vector<float> a, b, smax;
    double v_scale = 1, base = 0;
};
void slice_slopes(const std::vector<double>& d, const Terrain& terrain, float max_height, double eye_y,
                  SliceSlopes& out);

// Window depth of every slice (eq. 7) for the shear camera, whose view axis
// is F: one number per slice, shared by all columns (Algorithm 2).
void slice_window_depths(const Camera& camera, const Slices& slices, std::vector<float>& out);

// The ray slopes of the cast rows, bottom-up (non-decreasing), with a +inf
// sentinel at m[count].
struct Rows {
    std::vector<float> m;
    int count = 0;
    bool even = false; // evenly spaced in slope (shear): RowSearch guesses within a row
};

// Shear rows: m_j = (v_j + fp tan p) / fp, the horizon shifted by fp tan(pitch).
void shear_rows(const Camera& camera, Rows& out);

// Geometry of the tilted camera's rows (DESIGN sec. 2, tilt): the ray through
// (u, v) is F' + (u/fp) R + (v/fp) U' = w F + (u/fp) R + (sin p + (v/fp) cos p) Y
// with w = cos p - (v/fp) sin p, i.e. per unit of depth along F it goes
// sideways u/(fp w) and up m = (sin p + (v/fp) cos p)/w. Its view depth along
// F' is (depth along F)/w. Rows whose rays point nearly straight up or down
// (w < w_max/4) would need planes fanning out without bound: they are not
// cast (the ray marcher takes them).
struct TiltRows {
    std::vector<double> w, m; // per image row r (top-down): F component and slope of the row's rays
    int j_lo = 0, j_hi = 0;   // rows cast, bottom-up index range [j_lo, j_hi)
    double w_min = 1, w_max = 1; // over the rows cast
};
void tilt_rows(const Camera& camera, TiltRows& out);
// The cast rows [j_lo, j_hi) of a tilted camera as Rows (not evenly spaced).
void tilt_cast_rows(const TiltRows& tilt, Rows& out);

// The horizontal direction F + a_c R of each cast column's vertical plane.
// Shear: column c's own plane, a_c = u_c / fp.
void shear_column_planes(const Camera& camera, std::vector<double>& a);
// Tilt, exact: planes spaced so that a tilted pixel is never more than
// 1/kTiltPlanes of its width from one (at the row where pixels are
// narrowest), covering the tilted frustum's rows cast. Returns the planes
// per unit of a (the cast's fp_h).
constexpr double kTiltPlanes = 2.0;
double tilt_column_planes(const Camera& camera, const TiltRows& tilt, std::vector<double>& a);
// Tilt, Guedes: each column the plane of its pixel on the centre row, a_c = u_c / (fp cos p).
void guedes_column_planes(const Camera& camera, std::vector<double>& a);

// The cast columns: plane directions a (input) and what is derived from them.
// The slices on the terrain form one interval per column (a straight line
// leaves a rectangle once), so the cast's inner loop needs no bounds test.
struct Columns {
    std::vector<double> a;      // plane: horizontal direction F + a R
    std::vector<double> ux, uz; // grid units per unit of view depth along the plane
    std::vector<int> k0, k1;    // slices [k0, k1) on the terrain (empty: k0 == k1)
};
void clip_columns(const ViewAxes& view, const Terrain& terrain, const Slices& slices, Columns& columns);

// The shear cast's guess of the row a sample reaches (RowSearch), computed
// from the raw height in fixed point: (raw ga + gb) >> kGuessBits. RowSearch's
// map from sigma folded into each slice's sigma = raw a_k + b_k. RowSearch
// corrects any guess to the exact row; this one is within a row. Saturated so
// that the sum cannot overflow (the guess is then merely far off, for absurd
// cameras). kGuessBits: a raw height of 2^16 times a rounding error of 2^-25
// rows is under 1/512 row.
constexpr int kGuessBits = 24;
struct SliceGuess {
    std::int64_t ga, gb; // fixed-point guess
    float a, b;          // SliceSlopes a[k], b[k]: sigma = raw a + b
};
void slice_guesses(const SliceSlopes& slopes, const Rows& rows, std::vector<SliceGuess>& out);

// The eye distance past which fog is not looked up (FogTable's range): the
// far plane along the longest ray of the view, with a margin.
float shear_fog_reach(const Camera& camera, const Rows& rows);
float tilt_fog_reach(const Camera& camera);

} // namespace overflight
