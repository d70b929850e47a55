#pragma once
// One horizon sweep per sun direction for every renderer of a terrain that
// needs its cast shadows: the ceiling (what GL objects and meshes read,
// gl/ShadowCeilingTexture) and the mask (what a ray caster's lighting reads,
// SunLight.h) written by one pass of sweep_shadow (HorizonSweep.h), rather
// than one sweep of each by each of them when the sun moves (`fly`'s
// time-of-day keys: the ray caster casting the next frame on a task while the
// compositor draws this one).
//
// A moved sun is swept anew rather than answered from each sample's horizon
// slope along the azimuth (Stewart sec. 3: any elevation at that azimuth
// then a compare): the time-of-day keys move the azimuth with the elevation,
// and that horizon needs a convex hull per sun line and a tangent per sample,
// more than twice the instructions of the running maximum the sweep keeps
// for one elevation (README, sun shadows).
//
// Thread safe: the first caller for a direction sweeps, a concurrent caller
// for the same direction waits for it and shares the result. The latest
// result is kept; a result still held by a caller stays valid after the sun
// moved on.
#include "core/HorizonSweep.h"
#include "core/Terrain.h"

#include <glm/vec3.hpp>

#include <cstdint>
#include <memory>
#include <mutex>
#include <vector>

namespace overflight {

struct SunShadow {
    glm::vec3 sun_dir{0.0f};         // unit, what it was swept for
    ShadowCeiling ceiling;           // sweep_shadow_ceiling for sun_dir
    std::vector<std::uint8_t> mask;  // sweep_shadow_mask for sun_dir (1 = shadowed)
};

class SharedSunShadow {
public:
    // Keeps a reference to terrain (it must outlive this object).
    explicit SharedSunShadow(const Terrain& terrain) : terrain_(terrain) {}

    // The terrain's shadow for the sun direction `sun_dir` (towards the sun,
    // any length > 0; normalized as every consumer normalizes it), swept now
    // unless it is the latest one's.
    std::shared_ptr<const SunShadow> get(const glm::vec3& sun_dir);
    // How many sweeps get() has run.
    long long sweeps() const;

private:
    const Terrain& terrain_;
    mutable std::mutex mutex_;
    std::shared_ptr<SunShadow> latest_;
    long long sweeps_ = 0;
};

} // namespace overflight
