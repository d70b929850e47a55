#include "core/Scene.h"

namespace overflight {

const char* to_string(ObjectKind k) {
    switch (k) {
    case ObjectKind::Box: return "box";
    case ObjectKind::House: return "house";
    case ObjectKind::Vehicle: return "vehicle";
    case ObjectKind::Tower: return "tower";
    case ObjectKind::Model: return "model";
    }
    return "box";
}

void Scene::append(const Scene& other) {
    objects.insert(objects.end(), other.objects.begin(), other.objects.end());
    lines.insert(lines.end(), other.lines.begin(), other.lines.end());
}

} // namespace overflight
