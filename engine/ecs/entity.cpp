#include "engine/ecs/entity.hpp"

#include <cassert>

namespace aloha {

Entity EntityPool::create() {
    ++alive_count_;
    if (!free_.empty()) {
        const uint32_t index = free_.back();
        free_.pop_back();
        alive_[index] = 1;
        return Entity{index, generations_[index]};
    }
    assert(generations_.size() < UINT32_MAX && "entity index space exhausted");
    const auto index = static_cast<uint32_t>(generations_.size());
    generations_.push_back(0);
    alive_.push_back(1);
    return Entity{index, 0};
}

bool EntityPool::destroy(Entity e) {
    if (!valid(e)) return false;
    alive_[e.index] = 0;
    --alive_count_;
    // Retire the slot instead of wrapping its generation: a stale handle must never match again.
    if (generations_[e.index] < kMaxGeneration) {
        ++generations_[e.index];
        free_.push_back(e.index);
    }
    return true;
}

void EntityPool::reserve(size_t count) {
    generations_.reserve(count);
    alive_.reserve(count);
}

void EntityPool::clear() {
    for (size_t i = generations_.size(); i-- > 0;) {
        if (alive_[i] != 0) destroy(Entity{static_cast<uint32_t>(i), generations_[i]});
    }
}

}  // namespace aloha
