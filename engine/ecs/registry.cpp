#include "engine/ecs/registry.hpp"

#include <cstdio>
#include <cstdlib>

namespace aloha {

Registry::~Registry() { groups_.clear(); }

void Registry::abort_on_dead_entity(const char* call, Entity e) {
    std::fprintf(stderr, "aloha: Registry::%s on a dead or stale entity (index %u, generation %u)\n", call,
                 static_cast<unsigned>(e.index), static_cast<unsigned>(e.generation));
    std::abort();
}

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

ViewCache& Registry::view_cache(std::span<const ComponentTypeId> key) const {
    const std::lock_guard<std::mutex> lock(caches_mutex_);
    for (const auto& c : caches_) {
        if (c->is_for(key)) return *c;
    }
    std::vector<const StorageBase*> storages;
    for (const ComponentTypeId id : key) {
        assert(id < storages_.size() && storages_[id] && "a cached view's storages must exist");
        storages.push_back(storages_[id].get());
    }
    caches_.push_back(std::make_unique<ViewCache>(key, storages));
    return *caches_.back();
}

}  // namespace aloha
