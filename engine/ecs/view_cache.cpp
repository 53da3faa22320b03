#include "engine/ecs/view_cache.hpp"

#include <algorithm>
#include <cassert>

namespace aloha {

ViewCache::ViewCache(std::span<const ComponentTypeId> key, std::span<const StorageBase* const> storages)
    : key_(key.begin(), key.end()), storages_(storages.begin(), storages.end()), now_(storages.size()) {
    assert(key.size() == storages.size() && !storages.empty());
    assert(std::none_of(storages.begin(), storages.end(), [](const StorageBase* s) { return s == nullptr; }));
}

bool ViewCache::is_for(std::span<const ComponentTypeId> key) const {
    return std::equal(key.begin(), key.end(), key_.begin(), key_.end());
}

const SlotTable* ViewCache::acquire() {
    const std::lock_guard<std::mutex> lock(mutex_);
    for (size_t i = 0; i < storages_.size(); ++i) now_[i] = storages_[i]->layout_version();
    if (table_.current(now_)) {
        ++table_calls_;
        return &table_;
    }
    if (seen_ == now_) {
        table_.build(storages_, now_);
        ++table_calls_;
        return &table_;
    }
    seen_ = now_;
    ++stateless_calls_;
    return nullptr;
}

size_t ViewCache::builds() const {
    const std::lock_guard<std::mutex> lock(mutex_);
    return table_.rebuilds();
}

size_t ViewCache::table_calls() const {
    const std::lock_guard<std::mutex> lock(mutex_);
    return table_calls_;
}

size_t ViewCache::stateless_calls() const {
    const std::lock_guard<std::mutex> lock(mutex_);
    return stateless_calls_;
}

}  // namespace aloha
