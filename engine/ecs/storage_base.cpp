#include "engine/ecs/storage_base.hpp"

#include <algorithm>

#include "engine/ecs/group_data.hpp"

namespace aloha {

detail::SparsePage& StorageBase::sparse_page(uint32_t index) {
    const uint32_t page = index / kPageSize;
    if (page >= sparse_.size()) {
        sparse_.resize(page + 1, &detail::kAbsentPage);
        owned_pages_.resize(page + 1);
    }
    if (!owned_pages_[page]) {
        owned_pages_[page] = std::make_unique<detail::SparsePage>(detail::kAbsentPage);
        sparse_[page] = owned_pages_[page].get();
    }
    return *owned_pages_[page];
}

void StorageBase::push_entity(Entity e) {
    detail::SparsePage& page = sparse_page(e.index);
    // An index holds at most one entity: a stale handle must not overwrite a live one's entry.
    assert(page.dense[e.index % kPageSize] == kAbsent && "entity index already present in this storage");
    page.dense[e.index % kPageSize] = static_cast<uint32_t>(dense_.size());
    page.generation[e.index % kPageSize] = e.generation;
    dense_.push_back(e);
    ++layout_version_;
}

void StorageBase::notify_construct(Entity e) {
    if (owner_ != nullptr) owner_->on_construct(e);
}

bool StorageBase::remove(Entity e) {
    if (!contains(e)) return false;
    if (owner_ != nullptr) owner_->on_destroy(e);  // moves e out of the group's front range
    const uint32_t pos = sparse().position(e.index);
    const auto last = static_cast<uint32_t>(dense_.size() - 1);
    if (pos != last) {
        const Entity moved = dense_[last];
        dense_[pos] = moved;
        set_position(moved.index, pos);  // its generation is unchanged
    }
    pop_component(pos);
    dense_.pop_back();
    set_entry(e.index, kAbsent, kAbsent);
    ++layout_version_;
    return true;
}

void StorageBase::clear() {
    for (const Entity e : dense_) set_entry(e.index, kAbsent, kAbsent);
    dense_.clear();
    clear_components();
    ++layout_version_;
    if (owner_ != nullptr) owner_->reset();
}

void StorageBase::swap_positions(size_t a, size_t b) {
    if (a == b) return;
    const Entity ea = dense_[a];
    const Entity eb = dense_[b];
    dense_[a] = eb;
    dense_[b] = ea;
    set_position(ea.index, static_cast<uint32_t>(b));
    set_position(eb.index, static_cast<uint32_t>(a));
    swap_components(a, b);
    ++layout_version_;
}

void StorageBase::apply_swaps(std::span<const SwapPair> swaps) {
    for (const SwapPair s : swaps) std::swap(dense_[s.a], dense_[s.b]);
    swap_component_sequence(swaps);
    for (const SwapPair s : swaps) {
        for (const uint32_t pos : {s.a, s.b}) set_position(dense_[pos].index, pos);
    }
    if (!swaps.empty()) ++layout_version_;
}

bool StorageBase::consistent() const {
    if (sparse_.size() != owned_pages_.size()) return false;
    size_t present = 0;
    for (size_t page = 0; page < sparse_.size(); ++page) {
        const detail::SparsePage* entries = sparse_[page];
        if (owned_pages_[page] ? entries != owned_pages_[page].get() : entries != &detail::kAbsentPage) {
            return false;
        }
        for (uint32_t i = 0; i < kPageSize; ++i) {
            const SparseEntry s{entries->dense[i], entries->generation[i]};
            if (s.dense == kAbsent) {
                if (s.generation != kAbsent) return false;
                continue;
            }
            // A present entry names a dense position holding exactly this index and generation.
            if (s.dense >= dense_.size()) return false;
            const Entity e = dense_[s.dense];
            if (e.index != page * kPageSize + i || e.generation != s.generation) return false;
            ++present;
        }
    }
    // Every dense position is named by its own entry (so no index appears twice).
    if (present != dense_.size()) return false;
    for (size_t p = 0; p < dense_.size(); ++p) {
        if (find(dense_[p]) != p) return false;
    }
    return true;
}

}  // namespace aloha
