// Generational entity handles and the pool that hands them out and recycles their indices.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

namespace aloha {

/// A generational handle: `index` names a slot, `generation` says which life of that slot.
/// A destroyed entity's handle never matches a later entity in the same slot.
struct Entity {
    uint32_t index = UINT32_MAX;       ///< slot in the registry (UINT32_MAX for the null entity)
    uint32_t generation = UINT32_MAX;  ///< life of the slot this handle refers to

    /// Packs index (low 32 bits) and generation (high 32 bits) into one integer, e.g. for hashing.
    [[nodiscard]] constexpr uint64_t bits() const {
        return (uint64_t{generation} << 32) | uint64_t{index};
    }
    /// Two handles are equal when index and generation both match.
    friend constexpr bool operator==(Entity a, Entity b) = default;
};

/// The handle that never names an entity.
inline constexpr Entity kNullEntity{};

/// Hands out entity handles, recycles freed indices (LIFO) and bumps their generation on free.
/// A slot whose generation would reach the reserved values is retired and never reused.
class EntityPool {
public:
    /// Largest generation a live entity may have; the values above are reserved (null, pending).
    static constexpr uint32_t kMaxGeneration = UINT32_MAX - 2;

    /// Returns a fresh live handle.
    Entity create();
    /// Frees `e`; returns false (and does nothing) when `e` is not alive.
    bool destroy(Entity e);
    /// True when `e` names a live entity (index in range, slot alive, same generation).
    [[nodiscard]] bool valid(Entity e) const {
        return e.index < generations_.size() && alive_[e.index] != 0 &&
               generations_[e.index] == e.generation;
    }
    /// Number of live entities.
    [[nodiscard]] size_t alive() const { return alive_count_; }
    /// Number of slots ever created (live, free or retired).
    [[nodiscard]] size_t capacity() const { return generations_.size(); }
    /// The live handle in slot `index`, or kNullEntity when the slot is free.
    [[nodiscard]] Entity at(uint32_t index) const {
        if (index >= generations_.size() || alive_[index] == 0) return kNullEntity;
        return Entity{index, generations_[index]};
    }
    /// Reserves room for `count` slots.
    void reserve(size_t count);
    /// Frees every live entity (bumping generations so old handles stay invalid).
    void clear();

private:
    std::vector<uint32_t> generations_;
    std::vector<uint8_t> alive_;
    std::vector<uint32_t> free_;
    size_t alive_count_ = 0;
};

}  // namespace aloha
