#include "engine/ecs/registry.hpp"

namespace aloha {

Registry::~Registry() { groups_.clear(); }

bool Registry::destroy(Entity e) {
    if (!entities_.valid(e)) return false;
    for (const auto& s : storages_) {
        if (s) s->remove(e);
    }
    return entities_.destroy(e);
}

void Registry::clear() {
    for (const auto& s : storages_) {
        if (s) s->clear();
    }
    entities_.clear();
}

}  // namespace aloha
