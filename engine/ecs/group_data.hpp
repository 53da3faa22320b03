// The type-erased state of an owning group: which storages it owns and how many entities sit
// packed, in the same order, at the front of each of them. Also key sorting for LOD grouping.
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <numeric>
#include <span>
#include <vector>

#include "engine/ecs/storage_base.hpp"

namespace aloha {

/// A run of equal keys in a sorted key array: positions [begin, end) all have `key`.
struct KeyRange {
    uint32_t key = 0;
    size_t begin = 0;
    size_t end = 0;
};

/// Appends to `out` (after clearing it) one KeyRange per run of equal values in `sorted_keys`.
void key_ranges(std::span<const uint32_t> sorted_keys, std::vector<KeyRange>& out);

/// Allocating convenience form of key_ranges.
[[nodiscard]] std::vector<KeyRange> key_ranges(std::span<const uint32_t> sorted_keys);

/// Owning-group bookkeeping. Entities having every owned component occupy dense positions
/// [0, size()) of each owned storage, position i being the same entity in all of them.
class GroupData {
public:
    /// Takes ownership of `owned` storages (each must have no owner) and packs existing entities.
    explicit GroupData(std::vector<StorageBase*> owned);
    /// Releases the storages (they keep their data, unowned).
    ~GroupData();
    GroupData(const GroupData&) = delete;
    GroupData& operator=(const GroupData&) = delete;

    /// Number of entities in the group.
    [[nodiscard]] size_t size() const { return size_; }
    /// The owned storages, in the order given at construction.
    [[nodiscard]] std::span<StorageBase* const> owned() const { return owned_; }
    /// True when the group owns exactly the storages of the given (sorted) type ids.
    [[nodiscard]] bool owns_exactly(std::span<const ComponentTypeId> sorted_types) const;

    /// Storage hook after `e` gained an owned component: moves it into the group if complete.
    void on_construct(Entity e);
    /// Storage hook before `e` loses an owned component: moves it out of the group.
    void on_destroy(Entity e);
    /// Storage hook when an owned storage was cleared: the group becomes empty.
    void reset() { size_ = 0; }

    /// Stable-sorts the group by `keys` (keys[i] belongs to group position i; size must equal
    /// size()) and permutes `keys` alongside. Returns false, touching nothing, when already
    /// sorted; otherwise moves only the entities that change place.
    bool sort_by_key(std::span<uint32_t> keys);
    /// Makes equal keys contiguous in ascending key order without keeping the order inside a
    /// key (in-place bucket partition). Moves only misplaced entities, one swap each at most, so
    /// it is the cheap per-frame path when few keys changed. Permutes `keys` alongside; returns
    /// false when nothing moved.
    bool partition_by_key(std::span<uint32_t> keys);
    /// Stable-sorts the group with `less(i, j)` comparing group positions i and j (before sorting).
    /// Returns false when nothing moved.
    template <class Less>
    bool sort(Less less) {
        perm_.resize(size_);
        std::iota(perm_.begin(), perm_.end(), 0u);
        std::stable_sort(perm_.begin(), perm_.end(), [&](uint32_t a, uint32_t b) { return less(a, b); });
        return apply_permutation(perm_);
    }
    /// Reorders every owned storage so new position i holds the entity at old position perm[i]
    /// (perm must be a permutation of [0, size())). Returns false when perm is the identity.
    bool apply_permutation(std::span<const uint32_t> perm);

private:
    std::vector<StorageBase*> owned_;
    size_t size_ = 0;
    // Scratch kept across calls so sorting allocates nothing in steady state.
    std::vector<uint32_t> perm_;
    std::vector<uint32_t> counts_;
    std::vector<uint32_t> next_;
    std::vector<uint32_t> sorted_keys_;
    std::vector<uint8_t> visited_;
    std::vector<SwapPair> swaps_;
};

}  // namespace aloha
