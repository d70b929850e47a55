// One sweep per sun direction, shared. See SharedSunShadow.h.
#include "core/SharedSunShadow.h"

#include "core/Parallel.h"

#include <glm/geometric.hpp>

namespace overflight {

std::shared_ptr<const SunShadow> SharedSunShadow::get(const glm::vec3& sun_dir) {
    const glm::vec3 sun = glm::length(sun_dir) > 0 ? glm::normalize(sun_dir) : glm::vec3(0, 1, 0);
    const std::lock_guard lock(mutex_);
    if (latest_ && latest_->sun_dir == sun) return latest_;
    // The previous result's storage is reused when no caller holds it any
    // more: 5 bytes a sample, which a fresh allocation would fault in page
    // by page on every move of the sun.
    std::shared_ptr<SunShadow> next = latest_ && latest_.use_count() == 1 ? std::move(latest_) : std::make_shared<SunShadow>();
    latest_.reset();
    // Isolated: while it holds the lock, this thread takes no other task
    // (one that might wait for the lock in its turn).
    parallel::isolate([&] { sweep_shadow(terrain_, sun, next->ceiling, next->mask); });
    next->sun_dir = sun;
    ++sweeps_;
    latest_ = std::move(next);
    return latest_;
}

long long SharedSunShadow::sweeps() const {
    const std::lock_guard lock(mutex_);
    return sweeps_;
}

} // namespace overflight
