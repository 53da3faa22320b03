#include "engine/ecs/storage_base.hpp"

#include <algorithm>

#include "engine/ecs/group_data.hpp"

namespace aloha {

uint32_t& StorageBase::sparse_slot(uint32_t index) {
    const uint32_t page = index / kPageSize;
    if (page >= sparse_.size()) sparse_.resize(page + 1);
    if (!sparse_[page]) {
        sparse_[page] = std::make_unique<uint32_t[]>(kPageSize);
        std::fill_n(sparse_[page].get(), kPageSize, kAbsent);
    }
    return sparse_[page][index % kPageSize];
}

void StorageBase::push_entity(Entity e) {
    assert(!contains(e));
    sparse_slot(e.index) = static_cast<uint32_t>(dense_.size());
    dense_.push_back(e);
}

void StorageBase::notify_construct(Entity e) {
    if (owner_ != nullptr) owner_->on_construct(e);
}

bool StorageBase::remove(Entity e) {
    if (!contains(e)) return false;
    if (owner_ != nullptr) owner_->on_destroy(e);  // moves e out of the group's front range
    const uint32_t pos = sparse_[e.index / kPageSize][e.index % kPageSize];
    const uint32_t last = static_cast<uint32_t>(dense_.size() - 1);
    if (pos != last) {
        const Entity moved = dense_[last];
        dense_[pos] = moved;
        sparse_[moved.index / kPageSize][moved.index % kPageSize] = pos;
    }
    pop_component(pos);
    dense_.pop_back();
    sparse_[e.index / kPageSize][e.index % kPageSize] = kAbsent;
    return true;
}

void StorageBase::clear() {
    for (const Entity e : dense_) sparse_[e.index / kPageSize][e.index % kPageSize] = kAbsent;
    dense_.clear();
    clear_components();
    if (owner_ != nullptr) owner_->reset();
}

void StorageBase::swap_positions(size_t a, size_t b) {
    if (a == b) return;
    const Entity ea = dense_[a];
    const Entity eb = dense_[b];
    dense_[a] = eb;
    dense_[b] = ea;
    sparse_[ea.index / kPageSize][ea.index % kPageSize] = static_cast<uint32_t>(b);
    sparse_[eb.index / kPageSize][eb.index % kPageSize] = static_cast<uint32_t>(a);
    swap_components(a, b);
}

void StorageBase::apply_swaps(std::span<const SwapPair> swaps) {
    for (const SwapPair s : swaps) std::swap(dense_[s.a], dense_[s.b]);
    swap_component_sequence(swaps);
    for (const SwapPair s : swaps) {
        for (const uint32_t pos : {s.a, s.b}) {
            const Entity e = dense_[pos];
            sparse_[e.index / kPageSize][e.index % kPageSize] = pos;
        }
    }
}

}  // namespace aloha
