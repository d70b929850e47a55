// Based on: Schlick (1994) and Tessendorf (2001) through core/WaterSurface.h;
// the mirrored ray marched as Szenberg 1997 sec. 4's plain ray casting
// (RayMarcher). See WaterPass.h.
#include "raycast/WaterPass.h"

#include "core/Parallel.h"
#include "core/WaterSurface.h"
#include "raycast/Atmosphere.h"
#include "raycast/RayMarcher.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <atomic>
#include <cmath>

namespace overflight {

namespace {

glm::vec3 unit_rgb(Rgb8 c) { return glm::vec3(c.r, c.g, c.b) / 255.0f; }

// The pixel's points on the near and far planes, inverse_vp * (nx, ny, -+1, 1)
// divided by w. GLM sums a matrix times a vector as (m0 x + m1 y) + (m2 z +
// m3 w); so does this, with the column term m0 nx, the row term m1 ny and
// the planes' m2 z + m3 computed once: the same values, bit for bit, for a
// fraction of the work per pixel.
struct Unprojection {
    std::vector<glm::dvec4> columns; // m0 nx per column
    glm::dvec4 m1;                    // the row term's column
    glm::dvec4 near_plane, far_plane; // m2 z + m3 w at z = -1 and 1 (w = 1)
    int height = 0;

    // The ray through a pixel: m0 nx + m1 ny, and its points on the near
    // and far planes.
    struct PixelRay {
        glm::dvec4 xy;
        glm::dvec3 a, b;
    };

    Unprojection(const glm::dmat4& m, const Camera& camera) : m1(m[1]), height(camera.height) {
        columns.resize(std::size_t(camera.width));
        for (int col = 0; col < camera.width; ++col)
            columns[std::size_t(col)] = m[0] * ((col + 0.5) / camera.width * 2.0 - 1.0);
        near_plane = m[2] * -1.0 + m[3] * 1.0;
        far_plane = m[2] * 1.0 + m[3] * 1.0;
    }
    glm::dvec4 row_term(int row) const { return m1 * (1.0 - (row + 0.5) / height * 2.0); }
    PixelRay ray(int col, const glm::dvec4& row) const {
        const glm::dvec4 xy = columns[std::size_t(col)] + row;
        const glm::dvec4 an = xy + near_plane, bn = xy + far_plane;
        return {xy, glm::dvec3(an) / an.w, glm::dvec3(bn) / bn.w};
    }
};

// All levels, up to the 1x1 block of the whole terrain.
constexpr int kPyramidLevels = 31;

} // namespace

WaterPass::WaterPass(const Terrain& terrain, SharedSunShadow* sun_shadow)
    : terrain_(terrain), top_(terrain.max_height()), albedo_lighting_(terrain, LightOutput::Colors, sun_shadow),
      pyramid_(terrain, kPyramidLevels) {}

void WaterPass::set_colors(const std::vector<Rgb8>* colors, const Environment& env) {
    colors_ = terrain_.imagery() ? albedo_lighting_.colors(env) : colors;
}

long long WaterPass::apply(const Camera& camera, const Environment& env, SurfaceModel surface, ColorImage& color,
                           DepthImage& depth) const {
    if (!env.water || camera.eye.y == double(env.water_level)) return 0;
    if (camera.eye.y < double(env.water_level)) return apply_under(camera, env, surface, color, depth);
    const Terrain& t = terrain_;
    RayMarcher marcher(t, env);
    marcher.set_colors(colors_);
    if (skipping_) marcher.set_pyramid(&pyramid_);
    const RayMarcher::Frame frame = marcher.frame(camera);
    const double level = env.water_level;
    const double top = top_;
    const Unprojection pixels(frame.inverse_view_projection, camera);
    std::atomic<long long> flooded{0};
    parallel::for_each_index(0, camera.height, [&](int row) {
        long long n = 0;
        const glm::dvec4 row_term = pixels.row_term(row);
        for (int col = 0; col < camera.width; ++col) {
            const auto [ray, a, b] = pixels.ray(col, row_term);
            const glm::dvec3 d = b - a;
            if (!(d.y < 0.0)) continue;
            const double s = (level - a.y) / d.y;
            if (s < 0.0 || s > 1.0) continue;
            const glm::dvec3 p = a + s * d;
            if (!t.contains(float(p.x), float(p.z))) continue;
            const glm::dvec4 clip = frame.view_projection * glm::dvec4(p, 1.0);
            const float z = float(std::clamp((clip.z / clip.w + 1.0) * 0.5, 0.0, 1.0));
            float& behind = depth.at(col, row);
            if (!(z < behind)) continue;
            WaterSample w;
            w.view = glm::vec3(glm::normalize(d));
            w.normal = water_normal(float(p.x), float(p.z), env.water_time, t.h_scale());
            w.path = water_path(float(level) - t.height_bilinear(float(p.x), float(p.z)), w.view);
            // The mirrored ray, up to where it rises above the highest sample.
            const glm::dvec3 r(water_reflect(w.view, w.normal));
            const double reach = std::min(glm::length(d), (top - level) / r.y + t.h_scale());
            const RayMarcher::Hit hit = marcher.intersect(p, p + reach * r, surface);
            Rgb8 reflected;
            if (!hit.hit) reflected = env.atmosphere ? aerial_sky_rgb(frame.air, r) : sky_color(env, r);
            else if (env.atmosphere) reflected = aerial_rgb(frame.air, hit.surface, hit.point - p);
            else reflected = apply_fog(env, hit.surface, fog_factor(env, glm::length(hit.point - p)));
            w.reflected = unit_rgb(reflected);
            const WaterLight light = water_light(env, w);
            const Rgb8 c = to_rgb8(glm::clamp(light.surface, 0.0f, 1.0f));
            const Rgb8 own = env.atmosphere ? aerial_rgb(frame.air, c, p - camera.eye)
                                            : apply_fog(env, c, fog_factor(env, glm::length(p - camera.eye)));
            Rgb8& pixel = color.at(col, row);
            pixel = to_rgb8(unit_rgb(own) + (unit_rgb(pixel) - unit_rgb(own)) * light.behind);
            behind = z;
            ++n;
        }
        flooded += n;
    });
    return flooded.load();
}

long long WaterPass::apply_under(const Camera& camera, const Environment& env, SurfaceModel surface_model,
                                 ColorImage& color, DepthImage& depth) const {
    const Terrain& t = terrain_;
    RayMarcher marcher(t, env);
    const RayMarcher::Frame frame = marcher.frame(camera);
    const double level = env.water_level;
    const Unprojection pixels(frame.inverse_view_projection, camera);
    const glm::dvec4 m2 = frame.inverse_view_projection[2], m3 = frame.inverse_view_projection[3];
    const Rgb8 deep = to_rgb8(glm::clamp(water_deep_light(env), 0.0f, 1.0f));
    std::atomic<long long> surface{0};
    parallel::for_each_index(0, camera.height, [&](int row) {
        long long n = 0;
        const glm::dvec4 row_term = pixels.row_term(row);
        for (int col = 0; col < camera.width; ++col) {
            const auto [ray, a, b] = pixels.ray(col, row_term);
            const glm::dvec3 d = b - a;
            float& behind = depth.at(col, row);
            Rgb8& pixel = color.at(col, row);
            if (d.y > 0.0) {
                // The surface from below, where the ray rises to it before the terrain.
                const double s = (level - a.y) / d.y;
                const glm::dvec3 p = a + s * d;
                if (s >= 0.0 && s <= 1.0 && t.contains(float(p.x), float(p.z))) {
                    const glm::dvec4 clip = frame.view_projection * glm::dvec4(p, 1.0);
                    const float z = float(std::clamp((clip.z / clip.w + 1.0) * 0.5, 0.0, 1.0));
                    if (z < behind) {
                        const glm::vec3 view(glm::normalize(d));
                        const glm::vec3 normal = water_normal(float(p.x), float(p.z), env.water_time, t.h_scale());
                        const glm::dvec3 up(water_refract_up(view, normal));
                        const Rgb8 sky = env.atmosphere ? aerial_sky_rgb(frame.air, up) : sky_color(env, up);
                        const glm::vec3 c = water_underside(env, view, normal, unit_rgb(sky));
                        pixel = to_rgb8(glm::clamp(underwater_color(env, c, float(glm::length(p - camera.eye))), 0.0f, 1.0f));
                        behind = z;
                        ++n;
                        continue;
                    }
                }
            }
            if (behind < 1.0f) {
                // The terrain, seen through the water up to the level.
                const glm::dvec4 w = ray + m2 * (double(behind) * 2.0 - 1.0) + m3;
                glm::dvec3 q = glm::dvec3(w) / w.w;
                // The casts' depth is their slice's, up to a slice step off the
                // surface: the point goes along its ray onto the surface's
                // height there (for blocks, when a block top of that height is there).
                const glm::dvec3 v = q - camera.eye;
                if (v.y < 0.0) {
                    const bool blocks = surface_model == SurfaceModel::Blocks;
                    const double h = blocks ? t.height_nearest(float(q.x), float(q.z)) : t.height_bilinear(float(q.x), float(q.z));
                    const glm::dvec3 on = camera.eye + v * ((h - camera.eye.y) / v.y);
                    if (!blocks || double(t.height_nearest(float(on.x), float(on.z))) == h) q = on;
                }
                const double path = underwater_path(camera.eye, q, level);
                pixel = to_rgb8(glm::clamp(underwater_color(env, unit_rgb(pixel), float(path)), 0.0f, 1.0f));
            } else {
                pixel = deep; // no terrain, no surface over the terrain: the depths
            }
        }
        surface += n;
    });
    return surface.load();
}

} // namespace overflight
