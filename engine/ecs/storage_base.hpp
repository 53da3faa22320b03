// The type-erased face of a component storage: a sparse set of entities (paged sparse array ->
// dense index and generation, dense entity array) that the registry and groups drive without knowing T.
#pragma once

#include <array>
#include <cassert>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include "engine/ecs/entity.hpp"
#include "engine/ecs/type_id.hpp"

namespace aloha {

class GroupData;

/// One swap of two dense positions (used to permute storages identically).
struct SwapPair {
    uint32_t a;
    uint32_t b;
};

/// Sparse entry of one entity index: where its component sits in the dense arrays and which generation
/// of the index owns it. Absent indices hold {kAbsent, kAbsent}; a present one equals {p, dense[p].generation}.
struct SparseEntry {
    uint32_t dense;       ///< dense position, or kAbsent
    uint32_t generation;  ///< generation of the entity at `dense` (kAbsent when absent)
};

namespace detail {

/// Entries per sparse page (a power of two).
inline constexpr uint32_t kSparsePageSize = 4096;

/// One sparse page as two parallel arrays (dense positions, generations): a loop that only needs
/// positions reads 4 bytes per entity instead of 8, so a 64-byte line serves 16 indices.
struct SparsePage {
    std::array<uint32_t, kSparsePageSize> dense;       ///< dense position of each index, or kAbsent
    std::array<uint32_t, kSparsePageSize> generation;  ///< generation owning it (kAbsent when absent)
};

/// A sparse page whose entries are all absent.
constexpr SparsePage make_absent_page() {
    SparsePage page{};
    for (uint32_t& d : page.dense) d = UINT32_MAX;
    for (uint32_t& g : page.generation) g = UINT32_MAX;
    return page;
}

/// The shared, never-written page that stands in for sparse pages not allocated yet.
inline constexpr SparsePage kAbsentPage = make_absent_page();

}  // namespace detail

/// Read-only handle on a storage's sparse pages for tight loops. Valid until the storage gains a
/// sparse page (an emplace).
class SparseIndex {
public:
    /// Entries per sparse page (a power of two).
    static constexpr uint32_t kPageSize = detail::kSparsePageSize;
    /// Dense value (and generation) of an absent entry.
    static constexpr uint32_t kAbsent = UINT32_MAX;

    /// Wraps `count` page pointers (every one non-null: missing pages point at detail::kAbsentPage).
    SparseIndex(const detail::SparsePage* const* pages, size_t count) : pages_(pages), count_(count) {}

    /// The entry of entity index `index` (an absent entry when its page does not exist).
    [[nodiscard]] SparseEntry entry(uint32_t index) const {
        const detail::SparsePage& p = page(index);
        return SparseEntry{p.dense[index % kPageSize], p.generation[index % kPageSize]};
    }
    /// Where the dense position of entity index `index` is kept (for prefetching).
    [[nodiscard]] const uint32_t* position_slot(uint32_t index) const { return &page(index).dense[index % kPageSize]; }
    /// Where the generation of entity index `index` is kept (for prefetching).
    [[nodiscard]] const uint32_t* generation_slot(uint32_t index) const { return &page(index).generation[index % kPageSize]; }
    /// Dense position held for entity index `index`, whatever its generation, or kAbsent. Names `e`'s
    /// component only when the caller knows the index can only be held by `e` (a live entity of the
    /// registry that fills this storage: see View); find() checks the generation too.
    [[nodiscard]] uint32_t position(uint32_t index) const { return *position_slot(index); }
    /// Dense position of exactly this handle (index and generation), or kAbsent. Touches only the
    /// sparse page: an absent entry's dense value is kAbsent whatever generation it is asked for.
    [[nodiscard]] uint32_t find(Entity e) const {
        const SparseEntry s = entry(e.index);
        return s.generation == e.generation ? s.dense : kAbsent;
    }

private:
    [[nodiscard]] const detail::SparsePage& page(uint32_t index) const {
        const uint32_t p = index / kPageSize;
        return p < count_ ? *pages_[p] : detail::kAbsentPage;
    }

    const detail::SparsePage* const* pages_;
    size_t count_;
};

/// Sparse set of entities plus virtual hooks for the component array held by Storage<T>.
class StorageBase {
public:
    /// Entries per sparse page (a power of two).
    static constexpr uint32_t kPageSize = SparseIndex::kPageSize;
    /// Sparse value of an absent entity.
    static constexpr uint32_t kAbsent = SparseIndex::kAbsent;

    /// Creates an empty set for component type `type`.
    explicit StorageBase(ComponentTypeId type) : type_(type) {}
    virtual ~StorageBase() = default;
    StorageBase(const StorageBase&) = delete;
    StorageBase& operator=(const StorageBase&) = delete;

    /// The component type id this storage holds.
    [[nodiscard]] ComponentTypeId type() const { return type_; }
    /// Number of entities with this component.
    [[nodiscard]] size_t size() const { return dense_.size(); }
    /// True when empty.
    [[nodiscard]] bool empty() const { return dense_.empty(); }
    /// The dense entity array; element i owns component i.
    [[nodiscard]] std::span<const Entity> entities() const { return dense_; }

    /// True when exactly this handle (index and generation) has the component. Reads one sparse
    /// entry (its position and generation), never the dense array.
    [[nodiscard]] bool contains(Entity e) const { return find(e) != kAbsent; }
    /// Dense position of `e`; requires contains(e).
    [[nodiscard]] size_t index_of(Entity e) const {
        assert(contains(e));
        return sparse().position(e.index);
    }
    /// Dense position of `e`, or kAbsent when it lacks the component.
    [[nodiscard]] uint32_t find(Entity e) const { return sparse().find(e); }
    /// The sparse pages, for loops that look many entities up (see View).
    [[nodiscard]] SparseIndex sparse() const { return SparseIndex(sparse_.data(), sparse_.size()); }
    /// Checks every sparse/dense invariant (O(size + pages)): each dense position p has
    /// sparse[dense[p].index] == {p, dense[p].generation}, no two positions share an index, and
    /// every other entry is absent. For tests and debugging.
    [[nodiscard]] bool consistent() const;

    /// Removes `e`'s component (swap-and-pop); returns false when it had none.
    bool remove(Entity e);
    /// Removes every component.
    void clear();
    /// Reserves room for `count` entities in the dense array.
    void reserve_entities(size_t count) { dense_.reserve(count); }

    /// Swaps dense positions `a` and `b` (entities, components and sparse entries).
    void swap_positions(size_t a, size_t b);
    /// Applies `swaps` in order (each swaps two dense positions), the way groups permute storages.
    void apply_swaps(std::span<const SwapPair> swaps);

    /// Counts changes of which entity sits at which dense position (adds, removals, swaps, clears);
    /// equal values mean an unchanged layout, so a Query can keep positions it looked up.
    [[nodiscard]] uint64_t layout_version() const { return layout_version_; }

    /// The group that owns this storage, or nullptr.
    [[nodiscard]] GroupData* owner() const { return owner_; }
    /// Sets the owning group; requires no other owner (a storage belongs to at most one group).
    void set_owner(GroupData* group) { owner_ = group; }

protected:
    /// Appends `e` to the dense entity array and points its sparse entry at it; requires !contains(e).
    void push_entity(Entity e);
    /// Called after push_entity + component push: tells the owning group.
    void notify_construct(Entity e);
    /// Swaps component values at two dense positions.
    virtual void swap_components(size_t a, size_t b) = 0;
    /// Applies swap_components to each pair of `swaps` in order.
    virtual void swap_component_sequence(std::span<const SwapPair> swaps) = 0;
    /// Moves the last component into `pos` and pops the last one.
    virtual void pop_component(size_t pos) = 0;
    /// Drops every component value.
    virtual void clear_components() = 0;

private:
    // The writable page of `index`, allocated on first use.
    detail::SparsePage& sparse_page(uint32_t index);
    // Sets the entry of `index` (its page must exist: the entity is in the dense array).
    void set_entry(uint32_t index, uint32_t dense, uint32_t generation) {
        detail::SparsePage& p = *owned_pages_[index / kPageSize];
        p.dense[index % kPageSize] = dense;
        p.generation[index % kPageSize] = generation;
    }
    // Sets the dense position of `index`, keeping its generation (its page must exist).
    void set_position(uint32_t index, uint32_t dense) { owned_pages_[index / kPageSize]->dense[index % kPageSize] = dense; }

    ComponentTypeId type_;
    std::vector<const detail::SparsePage*> sparse_;               // read side; kAbsentPage where none
    std::vector<std::unique_ptr<detail::SparsePage>> owned_pages_;  // write side, same indexing; null where none
    std::vector<Entity> dense_;
    GroupData* owner_ = nullptr;
    uint64_t layout_version_ = 0;
};

}  // namespace aloha
