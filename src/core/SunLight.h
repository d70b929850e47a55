#pragma once
// The sun's light on the terrain's samples, for the renderers that paint
// sample colors (the ray casters): color = albedo x light with
//     light = ambient + sun_color * max(N . L, 0) * lit,
// N the sample's normal (Terrain::sample_normal), L the unit direction towards
// the sun, lit 0 where the terrain shadows the sample (HorizonSweep.h, when
// Environment::shadows is on) and 1 elsewhere. The GL programs' shade()
// (gl/GlProgram.cpp) is the same formula per fragment, so every terrain
// method shows the same brightness. A sun at or below the horizon
// (L.y <= 0) lights nothing: ambient only, in both.
//
// Based on: the CMSC 23700 hovercraft project, sec. 4.1 (directional sun and
// ambient light, Lambert's cosine law).
#include "core/DataSet.h"
#include "core/HorizonSweep.h"
#include "core/PackedNormals.h"
#include "core/SharedSunShadow.h"
#include "core/Terrain.h"

#include <glm/vec3.hpp>

#include <cstdint>
#include <memory>
#include <vector>

namespace overflight {

// Unit direction towards a sun at `azimuth_deg` (clockwise from north, as a
// compass: 90 = east) and `elevation_deg` above the horizon, in world
// coordinates (X east, Y up, Z south: north is -Z).
glm::vec3 sun_direction(double azimuth_deg, double elevation_deg);

struct SunAngles {
    double azimuth = 0, elevation = 0; // degrees; azimuth in [0, 360)
};
// Inverse of sun_direction (any length > 0).
SunAngles sun_angles(const glm::vec3& sun_dir);

// A day arc for the time-of-day key: sunrise due east at 6:00, the sun due
// south at 12:00 at kNoonElevation, sunset due west at 18:00, below the
// horizon (night, ambient light only) from 18:00 to 6:00. `hour` in [0, 24).
inline constexpr double kNoonElevation = 60.0;
glm::vec3 sun_at_hour(double hour);
// The hour of the arc whose azimuth is nearest to sun_dir's (6:00..18:00).
double hour_of_sun(const glm::vec3& sun_dir);

// The papers' look: the terrain's colors shown as they are (whatever light
// they hold is baked into them); the objects keep the sun. `--lighting
// baked` and the `1` key set it (Environment::baked).
void bake_lighting(Environment& env);
bool lighting_is_baked(const Environment& env);

// The light at a sample of normal `n` (unit): ambient + sun_color * max(n . L, 0) * lit.
glm::vec3 sample_light(const Environment& env, const glm::vec3& n, bool lit);

// What a lighting fills per sample: albedo x light (the terrain's colors
// lit), or the light alone as the color of an albedo of 128, so that 128 is a
// light of 1 (for renderers that take the albedo from imagery finer than the
// samples, raycast/ImageryTexels.h).
enum class LightOutput { Colors, Light };

// Fills `out` (resized to the terrain's samples) with albedo x light per
// sample, rounded to 8 bits, from the terrain's normals packed by
// pack_normals (within one color level of sample_light with
// Terrain::sample_normal: PackedNormals.h). `shadow` (null: nothing
// shadowed) must have been computed for env.sun_dir. Parallel over rows.
void light_colors(const Terrain& terrain, const PackedNormals& normals, const Environment& env,
                  const ShadowCeiling* shadow, std::vector<Rgb8>& out, LightOutput output = LightOutput::Colors);
// The same with the terrain's shadow as a mask (sweep_shadow_mask for
// env.sun_dir; 1 = shadowed): the same colors as with the ceiling it stands
// for, reading a byte per sample instead of a height and a ceiling.
void light_colors(const Terrain& terrain, const PackedNormals& normals, const Environment& env,
                  const std::vector<std::uint8_t>& shadow_mask, std::vector<Rgb8>& out,
                  LightOutput output = LightOutput::Colors);

// The terrain's shadow as a renderer that paints one color per sample needs
// it to end a shadow where the mesh ends it (halfway between a shadowed and a
// lit sample) rather than at a sample: the light mask (1 = shadowed) and each
// sample's color under the other light state (lit where the mask shadows it,
// shadowed where it does not), both one per sample. Null: nothing shadowed.
struct LightMask {
    const std::vector<std::uint8_t>* shadowed = nullptr;
    const std::vector<Rgb8>* other_colors = nullptr;
};

// light_colors for the mask, and into `other` each sample's color with its
// light state flipped (LightMask::other_colors): one pass for both.
void light_colors(const Terrain& terrain, const PackedNormals& normals, const Environment& env,
                  const std::vector<std::uint8_t>& shadow_mask, std::vector<Rgb8>& out, std::vector<Rgb8>& other,
                  LightOutput output = LightOutput::Colors);

// The lit colors of one terrain for the environment of the frame, recomputed
// only when the sun, its colors or Environment::shadows change (the horizon
// sweep only when the sun's direction does), so that a still sun costs a
// comparison per frame. The sweep writes the shadow mask alone
// (sweep_shadow_mask), which the light reads; or, given a SharedSunShadow,
// the light reads the mask of the sweep it shares with the other renderers
// of the terrain (the compositor's ceiling).
class TerrainLighting {
public:
    // Keeps a reference to terrain and to `shared` (null: sweeps its own
    // mask), which must outlive this object.
    explicit TerrainLighting(const Terrain& terrain, LightOutput output = LightOutput::Colors,
                             SharedSunShadow* shared = nullptr)
        : terrain_(terrain), output_(output), shared_(shared) {}

    // The colors to paint for `env`: nullptr when lighting is baked (the
    // terrain's own colors), else the lit colors; with LightOutput::Light,
    // the light (128 everywhere when baked). Valid until the next call.
    const std::vector<Rgb8>* colors(const Environment& env);
    // Changes each time colors() returns different colors.
    std::uint64_t version() const { return version_; }
    // The light mask behind the last colors() (empty when Environment::shadows
    // is off or lighting is baked). Valid until the next colors().
    LightMask light_mask() const;

private:
    const Terrain& terrain_;
    LightOutput output_;
    bool valid_ = false, baked_ = false;
    Environment lit_for_;
    SharedSunShadow* shared_;
    std::shared_ptr<const SunShadow> shared_shadow_; // shared_'s for shadow_for_
    std::vector<std::uint8_t> shadow_; // sweep_shadow_mask for shadow_for_, without shared_
    glm::vec3 shadow_for_{0.0f};
    bool shadow_valid_ = false;
    PackedNormals normals_; // packed on the first lit call
    std::vector<Rgb8> colors_;
    std::vector<Rgb8> other_colors_; // LightMask::other_colors, with shadows
    bool masked_ = false;            // colors_ are shadowed by the mask (shadow_ or shared_shadow_'s)
    std::uint64_t version_ = 0;
};

} // namespace overflight
