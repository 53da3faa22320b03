// View<Ts...>: iterates the entities that have every component Ts, driven by the smallest storage.
#pragma once

#include <algorithm>
#include <cstddef>
#include <tuple>
#include <type_traits>

#include "engine/ecs/storage.hpp"

namespace aloha {

/// The storage type a view element refers to: const storage for const components.
template <class T>
using StorageFor = std::conditional_t<std::is_const_v<T>, const Storage<std::remove_const_t<T>>,
                                      Storage<T>>;

/// Non-owning view over the storages of Ts (use `const T` for read-only access).
/// Structural changes to the viewed storages while iterating are not allowed: record them in a
/// CommandBuffer and apply it afterwards.
template <class... Ts>
class View {
    static_assert(sizeof...(Ts) > 0, "a view needs at least one component type");

public:
    /// Builds a view over the given storages; a null storage makes the view empty.
    explicit View(StorageFor<Ts>*... storages) : storages_(storages...) {}

    /// Calls fn(Entity, Ts&...) or fn(Ts&...) for each entity that has every Ts, in the dense
    /// order of the smallest storage.
    template <class Fn>
    void each(Fn&& fn) const {
        const StorageBase* driver = smallest();
        if (driver == nullptr) return;
        const std::span<const Entity> entities = driver->entities();
        for (size_t i = 0; i < entities.size(); ++i) {
            const Entity e = entities[i];
            // One sparse lookup per non-driving storage; the driver is addressed by position.
            const std::tuple<Ts*...> ptrs{element<Ts>(driver, i, e)...};
            if (((std::get<Ts*>(ptrs) == nullptr) || ...)) continue;
            if constexpr (std::is_invocable_v<Fn&, Entity, Ts&...>) {
                fn(e, *std::get<Ts*>(ptrs)...);
            } else {
                fn(*std::get<Ts*>(ptrs)...);
            }
        }
    }

    /// Number of entities the view visits (walks the driving storage).
    [[nodiscard]] size_t count() const {
        size_t n = 0;
        each([&n](Entity, Ts&...) { ++n; });
        return n;
    }
    /// Upper bound on the number of entities visited: the smallest storage's size.
    [[nodiscard]] size_t size_hint() const {
        const StorageBase* s = smallest();
        return s == nullptr ? 0 : s->size();
    }
    /// True when `e` has every Ts.
    [[nodiscard]] bool contains(Entity e) const {
        return ((std::get<StorageFor<Ts>*>(storages_) != nullptr &&
                 std::get<StorageFor<Ts>*>(storages_)->contains(e)) && ...);
    }

private:
    [[nodiscard]] const StorageBase* smallest() const {
        const StorageBase* best = nullptr;
        bool missing = false;
        auto consider = [&](const StorageBase* s) {
            if (s == nullptr) {
                missing = true;
            } else if (best == nullptr || s->size() < best->size()) {
                best = s;
            }
        };
        (consider(std::get<StorageFor<Ts>*>(storages_)), ...);
        return missing ? nullptr : best;
    }

    template <class T>
    T* element(const StorageBase* driver, size_t i, Entity e) const {
        StorageFor<T>* s = std::get<StorageFor<T>*>(storages_);
        if (static_cast<const StorageBase*>(s) == driver) return &s->components()[i];
        return s->try_get(e);
    }

    std::tuple<StorageFor<Ts>*...> storages_;
};

}  // namespace aloha
