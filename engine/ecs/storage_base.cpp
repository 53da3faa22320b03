#include "engine/ecs/storage_base.hpp"

#include <algorithm>

#include "engine/ecs/group_data.hpp"

namespace aloha {

namespace {

constexpr SparseEntry kAbsentEntry{StorageBase::kAbsent, StorageBase::kAbsent};

}  // namespace

SparseEntry& StorageBase::sparse_slot(uint32_t index) {
    const uint32_t page = index / kPageSize;
    if (page >= sparse_.size()) {
        sparse_.resize(page + 1, detail::kAbsentPage.data());
        owned_pages_.resize(page + 1);
    }
    if (!owned_pages_[page]) {
        owned_pages_[page] = std::make_unique<SparseEntry[]>(kPageSize);
        std::fill_n(owned_pages_[page].get(), kPageSize, kAbsentEntry);
        sparse_[page] = owned_pages_[page].get();
    }
    return owned_pages_[page][index % kPageSize];
}

void StorageBase::push_entity(Entity e) {
    SparseEntry& slot = sparse_slot(e.index);
    // An index holds at most one entity: a stale handle must not overwrite a live one's entry.
    assert(slot.dense == kAbsent && "entity index already present in this storage");
    slot = SparseEntry{static_cast<uint32_t>(dense_.size()), e.generation};
    dense_.push_back(e);
}

void StorageBase::notify_construct(Entity e) {
    if (owner_ != nullptr) owner_->on_construct(e);
}

bool StorageBase::remove(Entity e) {
    if (!contains(e)) return false;
    if (owner_ != nullptr) owner_->on_destroy(e);  // moves e out of the group's front range
    SparseEntry& removed = entry_of(e.index);
    const uint32_t pos = removed.dense;
    const auto last = static_cast<uint32_t>(dense_.size() - 1);
    if (pos != last) {
        const Entity moved = dense_[last];
        dense_[pos] = moved;
        entry_of(moved.index).dense = pos;  // its generation is unchanged
    }
    pop_component(pos);
    dense_.pop_back();
    removed = kAbsentEntry;
    return true;
}

void StorageBase::clear() {
    for (const Entity e : dense_) entry_of(e.index) = kAbsentEntry;
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
    entry_of(ea.index).dense = static_cast<uint32_t>(b);
    entry_of(eb.index).dense = static_cast<uint32_t>(a);
    swap_components(a, b);
}

void StorageBase::apply_swaps(std::span<const SwapPair> swaps) {
    for (const SwapPair s : swaps) std::swap(dense_[s.a], dense_[s.b]);
    swap_component_sequence(swaps);
    for (const SwapPair s : swaps) {
        for (const uint32_t pos : {s.a, s.b}) entry_of(dense_[pos].index).dense = pos;
    }
}

bool StorageBase::consistent() const {
    if (sparse_.size() != owned_pages_.size()) return false;
    size_t present = 0;
    for (size_t page = 0; page < sparse_.size(); ++page) {
        const SparseEntry* entries = sparse_[page];
        if (owned_pages_[page] ? entries != owned_pages_[page].get() : entries != detail::kAbsentPage.data()) {
            return false;
        }
        for (uint32_t i = 0; i < kPageSize; ++i) {
            const SparseEntry s = entries[i];
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
