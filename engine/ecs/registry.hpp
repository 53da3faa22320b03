// Registry: owns entities, one packed storage per component type, and the owning groups.
#pragma once

#include <algorithm>
#include <array>
#include <cassert>
#include <memory>
#include <mutex>
#include <span>
#include <tuple>
#include <type_traits>
#include <utility>
#include <vector>

#include "engine/ecs/entity.hpp"
#include "engine/ecs/group.hpp"
#include "engine/ecs/group_data.hpp"
#include "engine/ecs/storage.hpp"
#include "engine/ecs/query.hpp"
#include "engine/ecs/view.hpp"
#include "engine/ecs/view_cache.hpp"

namespace aloha {

/// The entity-component store. Not thread-safe for structural changes; concurrent reads and
/// writes of distinct component types through views/spans are fine (the scheduler's contract).
class Registry {
public:
    Registry() = default;
    ~Registry();
    Registry(const Registry&) = delete;
    Registry& operator=(const Registry&) = delete;

    /// Creates an entity with no components.
    Entity create() { return entities_.create(); }
    /// Destroys `e` and all its components; returns false when `e` was not alive.
    bool destroy(Entity e);
    /// True when `e` is alive (stale and null handles are not).
    [[nodiscard]] bool valid(Entity e) const { return entities_.valid(e); }
    /// Number of live entities.
    [[nodiscard]] size_t alive() const { return entities_.alive(); }
    /// The live handle in slot `index`, or kNullEntity.
    [[nodiscard]] Entity entity_at(uint32_t index) const { return entities_.at(index); }
    /// Reserves room for `count` entities.
    void reserve(size_t count) { entities_.reserve(count); }

    /// Gives live entity `e` a T built from `args` (replacing an existing one); returns it. A dead or stale
    /// `e` is a programmer error that aborts with a message in every build: stored, it would take the place
    /// of the live entity now in its slot (two entries for one index).
    template <class T, class... Args>
    T& emplace(Entity e, Args&&... args) {
        if (!valid(e)) [[unlikely]]
            abort_on_dead_entity("emplace", e);
        return storage<T>().emplace(e, std::forward<Args>(args)...);
    }
    /// The T of `e`; requires has<T>(e).
    template <class T>
    [[nodiscard]] T& get(Entity e) {
        return storage<T>().get(e);
    }
    /// The T of `e`, or nullptr when `e` is dead, stale or lacks T.
    template <class T>
    [[nodiscard]] T* try_get(Entity e) {
        Storage<T>* s = find_storage<T>();
        return s == nullptr ? nullptr : s->try_get(e);
    }
    /// The T of `e`, or nullptr when `e` is dead, stale or lacks T.
    template <class T>
    [[nodiscard]] const T* try_get(Entity e) const {
        const Storage<T>* s = find_storage<T>();
        return s == nullptr ? nullptr : s->try_get(e);
    }
    /// True when `e` is alive and has T.
    template <class T>
    [[nodiscard]] bool has(Entity e) const {
        const Storage<T>* s = find_storage<T>();
        return s != nullptr && s->contains(e);
    }
    /// Removes `e`'s T; returns false when it had none.
    template <class T>
    bool remove(Entity e) {
        Storage<T>* s = find_storage<T>();
        return s != nullptr && s->remove(e);
    }

    /// The storage of T, created on first use.
    template <class T>
    Storage<T>& storage() {
        const ComponentTypeId id = component_type_id<T>();
        if (id >= storages_.size()) storages_.resize(id + 1);
        if (!storages_[id]) storages_[id] = std::make_unique<Storage<T>>();
        return static_cast<Storage<T>&>(*storages_[id]);
    }
    /// The storage of T, or nullptr when none was created yet.
    template <class T>
    [[nodiscard]] Storage<T>* find_storage() {
        const ComponentTypeId id = component_type_id<T>();
        return id < storages_.size() ? static_cast<Storage<T>*>(storages_[id].get()) : nullptr;
    }
    /// The storage of T, or nullptr when none was created yet.
    template <class T>
    [[nodiscard]] const Storage<T>* find_storage() const {
        const ComponentTypeId id = component_type_id<T>();
        return id < storages_.size() ? static_cast<const Storage<T>*>(storages_[id].get()) : nullptr;
    }
    /// The type-erased storage for `id`, or nullptr.
    [[nodiscard]] StorageBase* storage_by_id(ComponentTypeId id) {
        return id < storages_.size() ? storages_[id].get() : nullptr;
    }

    /// A view over the entities having every Ts (`const T` for read-only); creates missing storages.
    /// It uses this registry's ViewCache for the list of Ts (constness ignored; see ViewCache for
    /// when the cache is read and when the stateless loop runs). Calls from several threads are fine
    /// once the storages exist (the scheduler's systems); it must not outlive the registry.
    template <class... Ts>
    [[nodiscard]] View<Ts...> view() {
        const std::tuple<StorageFor<Ts>*...> storages{&storage<std::remove_const_t<Ts>>()...};  // before the cache
        return View<Ts...>(&view_cache(cache_key<Ts...>()), std::get<StorageFor<Ts>*>(storages)...);
    }
    /// A read-only view, cached like the one above; a missing storage makes it empty (and uncached).
    template <class... Ts>
    [[nodiscard]] View<const Ts...> view() const {
        if (((find_storage<std::remove_const_t<Ts>>() == nullptr) || ...)) {
            return View<const Ts...>(find_storage<std::remove_const_t<Ts>>()...);
        }
        return View<const Ts...>(&view_cache(cache_key<Ts...>()), find_storage<std::remove_const_t<Ts>>()...);
    }

    /// A query over the entities having every Ts, to keep across frames (see Query); creates missing
    /// storages. It holds pointers into this registry, so it must not outlive it.
    template <class... Ts>
    [[nodiscard]] Query<Ts...> query() {
        return Query<Ts...>(&storage<std::remove_const_t<Ts>>()...);
    }

    /// The owning group of Ts, created (and packed) on first use. Each storage can be owned by one
    /// group only: asking for a group that overlaps an existing different group is a programmer
    /// error (asserted).
    template <class... Ts>
    [[nodiscard]] Group<Ts...> group() {
        std::array<ComponentTypeId, sizeof...(Ts)> ids{component_type_id<Ts>()...};
        std::sort(ids.begin(), ids.end());
        assert(std::adjacent_find(ids.begin(), ids.end()) == ids.end() && "duplicate group type");
        for (const auto& g : groups_) {
            if (g->owns_exactly(ids)) return Group<Ts...>(g.get(), &storage<Ts>()...);
        }
        std::vector<StorageBase*> owned{static_cast<StorageBase*>(&storage<Ts>())...};
        groups_.push_back(std::make_unique<GroupData>(std::move(owned)));
        return Group<Ts...>(groups_.back().get(), &storage<Ts>()...);
    }

    /// Destroys every entity and component (old handles stay invalid); storages and groups remain.
    void clear();

private:
    /// Prints which call got a dead or stale handle and aborts (the checks that stay in release builds).
    [[noreturn]] static void abort_on_dead_entity(const char* call, Entity e);
    // The component type ids of Ts (constness ignored), in order: the key of their ViewCache.
    template <class... Ts>
    static std::span<const ComponentTypeId> cache_key() {
        static const std::array<ComponentTypeId, sizeof...(Ts)> key{component_type_id<std::remove_const_t<Ts>>()...};
        return key;
    }
    // The ViewCache for the type list `key` (its storages must exist), created on first use. Thread-safe.
    ViewCache& view_cache(std::span<const ComponentTypeId> key) const;

    EntityPool entities_;
    std::vector<std::unique_ptr<StorageBase>> storages_;  // indexed by ComponentTypeId
    std::vector<std::unique_ptr<GroupData>> groups_;      // destroyed before storages_
    mutable std::mutex caches_mutex_;                      // guards caches_ (not the caches' contents)
    mutable std::vector<std::unique_ptr<ViewCache>> caches_;  // one per type list views asked for
};

}  // namespace aloha
