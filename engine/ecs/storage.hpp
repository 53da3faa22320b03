// Storage<T>: a sparse set whose component values sit in one contiguous array aligned with the
// dense entity array.
#pragma once

#include <cassert>
#include <span>
#include <type_traits>
#include <utility>
#include <vector>

#include "engine/ecs/storage_base.hpp"

namespace aloha {

/// Packed storage of component T (T must be move-constructible and move-assignable).
template <class T>
class Storage final : public StorageBase {
public:
    /// The component type.
    using value_type = T;

    /// Creates an empty storage.
    Storage() : StorageBase(component_type_id<T>()) {}

    /// Gives `e` a component built from `args` (replacing an existing one); returns it.
    /// Requires `e` to be alive (the registry checks). Invalidates references to other components.
    template <class... Args>
    T& emplace(Entity e, Args&&... args) {
        if (const uint32_t slot = find(e); slot != kAbsent) {
            components_[slot] = make(std::forward<Args>(args)...);
            return components_[slot];
        }
        components_.push_back(make(std::forward<Args>(args)...));
        push_entity(e);
        notify_construct(e);
        return components_[index_of(e)];  // the group may have moved it
    }
    /// The component of `e`; requires contains(e).
    [[nodiscard]] T& get(Entity e) { return components_[index_of(e)]; }
    /// The component of `e`; requires contains(e).
    [[nodiscard]] const T& get(Entity e) const { return components_[index_of(e)]; }
    /// The component of `e`, or nullptr when it has none (stale handles give nullptr).
    [[nodiscard]] T* try_get(Entity e) {
        const uint32_t slot = find(e);
        return slot == kAbsent ? nullptr : &components_[slot];
    }
    /// The component of `e`, or nullptr when it has none (stale handles give nullptr).
    [[nodiscard]] const T* try_get(Entity e) const {
        const uint32_t slot = find(e);
        return slot == kAbsent ? nullptr : &components_[slot];
    }
    /// All components, aligned with entities().
    [[nodiscard]] std::span<T> components() { return components_; }
    /// All components, aligned with entities().
    [[nodiscard]] std::span<const T> components() const { return components_; }
    /// Reserves room for `count` components.
    void reserve(size_t count) {
        components_.reserve(count);
        reserve_entities(count);
    }

protected:
    /// Swaps the component values at dense positions a and b.
    void swap_components(size_t a, size_t b) override {
        using std::swap;
        swap(components_[a], components_[b]);
    }
    /// Applies swap_components to each pair in order (one virtual call for the whole sequence).
    void swap_component_sequence(std::span<const SwapPair> swaps) override {
        using std::swap;
        for (const SwapPair s : swaps) swap(components_[s.a], components_[s.b]);
    }
    /// Moves the last value into `pos` and drops the last slot.
    void pop_component(size_t pos) override {
        if (pos + 1 != components_.size()) components_[pos] = std::move(components_.back());
        components_.pop_back();
    }
    /// Drops every value.
    void clear_components() override { components_.clear(); }

private:
    template <class... Args>
    static T make(Args&&... args) {
        if constexpr (std::is_aggregate_v<T>) {
            return T{std::forward<Args>(args)...};
        } else {
            return T(std::forward<Args>(args)...);
        }
    }

    std::vector<T> components_;
};

}  // namespace aloha
