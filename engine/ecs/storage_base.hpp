// The type-erased face of a component storage: a sparse set of entities (paged sparse array ->
// dense index, dense entity array) that the registry and groups drive without knowing T.
#pragma once

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

/// Sparse set of entities plus virtual hooks for the component array held by Storage<T>.
class StorageBase {
public:
    /// Entries per sparse page (a power of two).
    static constexpr uint32_t kPageSize = 4096;
    /// Sparse value of an absent entity.
    static constexpr uint32_t kAbsent = UINT32_MAX;

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

    /// True when exactly this handle (index and generation) has the component.
    [[nodiscard]] bool contains(Entity e) const {
        const uint32_t page = e.index / kPageSize;
        if (page >= sparse_.size() || !sparse_[page]) return false;
        const uint32_t slot = sparse_[page][e.index % kPageSize];
        return slot != kAbsent && dense_[slot] == e;
    }
    /// Dense position of `e`; requires contains(e).
    [[nodiscard]] size_t index_of(Entity e) const {
        assert(contains(e));
        return sparse_[e.index / kPageSize][e.index % kPageSize];
    }
    /// Dense position of `e`, or kAbsent when it lacks the component.
    [[nodiscard]] uint32_t find(Entity e) const {
        return contains(e) ? sparse_[e.index / kPageSize][e.index % kPageSize] : kAbsent;
    }

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
    uint32_t& sparse_slot(uint32_t index);

    ComponentTypeId type_;
    std::vector<std::unique_ptr<uint32_t[]>> sparse_;
    std::vector<Entity> dense_;
    GroupData* owner_ = nullptr;
};

}  // namespace aloha
