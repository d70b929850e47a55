#pragma once
// The one camera every renderer shares (DESIGN sec. 2). A camera is an eye, a
// heading, a pitch, a horizontal field of view, an image size and near/far.
//
//   F = (sin h, 0, cos h)   forward, horizontal (h = 0 faces south, +Z)
//   R = F x Y               right
//   fp = (W/2) / tan(fov/2) focal length in pixels
//   pixel (c, r) centre:  u = c + 0.5 - W/2,  v = H/2 - (r + 0.5)
//
// `shear` keeps the view plane vertical and moves the horizon by fp*tan(p)
// (Szenberg sec. 5.1, Fig. 6: an off-axis OpenGL frustum); `tilt` rotates the
// camera itself by p (Guedes). Depth is OpenGL window depth in [0,1] for near n
// and far f measured along the view axis: F for shear, F' for tilt.
#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

namespace overflight {

enum class Projection { Shear, Tilt };

const char* to_string(Projection p);

struct Camera {
    glm::dvec3 eye{0.0};
    double heading = 0.0;  // degrees
    double pitch = 0.0;    // degrees, positive looks up; |pitch| < 89
    double fov = 60.0;     // horizontal, degrees, (0, 180)
    int width = 1280;      // pixels
    int height = 720;
    double near = 1.0;     // world units along the view axis
    double far = 4096.0;
    Projection projection = Projection::Shear;

    // Throws Error("camera", ...) when the camera is unusable: far <= near,
    // near <= 0, fov outside (0, 180), |pitch| >= 89, size outside 1..16384,
    // a non-finite eye.
    void validate() const;

    glm::dvec3 forward() const;      // F, horizontal
    glm::dvec3 right() const;        // R = F x Y
    glm::dvec3 view_axis() const;    // F for shear, F' = cos p F + sin p Y for tilt
    glm::dvec3 view_up() const;      // Y for shear, U' = -sin p F + cos p Y for tilt
    double focal_px() const;         // fp

    // Pixel-centre offsets of DESIGN sec. 2 (column c from the left, row r from the top).
    double u_of(double col) const { return col + 0.5 - width * 0.5; }
    double v_of(double row) const { return height * 0.5 - (row + 0.5); }

    // Ray direction through image point (u, v), not normalised: its component
    // along view_axis() is 1, so t along it is the view depth.
    glm::dvec3 ray(double u, double v) const;

    // OpenGL matrices for this camera (right-handed eye space looking down -Z).
    glm::dmat4 view_matrix() const;
    glm::dmat4 projection_matrix() const;

    // Distance of a world point along the view axis (eye-space -z).
    double view_depth(const glm::dvec3& world) const;
    // OpenGL window depth of a view depth d (Szenberg eq. 4, 5, 7): (f - f n / d) / (f - n).
    double window_depth(double d) const { return (far - far * near / d) / (far - near); }
    // Inverse of window_depth.
    double view_depth_of_window(double wd) const { return far * near / (far - wd * (far - near)); }

    struct Projected {
        double col;    // x in pixels from the left edge (pixel centres at c + 0.5)
        double row;    // y in pixels from the top edge (pixel centres at r + 0.5)
        double depth;  // window depth
        bool in_front; // view depth > 0
    };
    // Projects a world point to the image, by the same math as the GL matrices.
    Projected project(const glm::dvec3& world) const;
};

} // namespace overflight
