// Group<Ts...>: the entities having every Ts, packed at the front of each owned storage in the
// same order, so span<T>() gives aligned contiguous arrays that jobs can run on directly.
#pragma once

#include <cassert>
#include <span>
#include <tuple>
#include <type_traits>

#include "engine/ecs/group_data.hpp"
#include "engine/ecs/storage.hpp"

namespace aloha {

/// Handle to an owning group obtained from Registry::group<Ts...>(); cheap to copy. Element i of
/// every span<T>() and of entities() is the same entity. Spans stay valid until a structural
/// change to an owned storage (emplace/remove/destroy, command-buffer apply, sort).
template <class... Ts>
class Group {
    static_assert(sizeof...(Ts) > 0, "a group needs at least one component type");
    static_assert((!std::is_const_v<Ts> && ...), "groups own their storages: use non-const types");

public:
    /// Wraps `data` (owning exactly the given storages); used by Registry::group.
    Group(GroupData* data, Storage<Ts>*... storages) : data_(data), storages_(storages...) {}

    /// Number of entities in the group.
    [[nodiscard]] size_t size() const { return data_->size(); }
    /// True when `e` is in the group.
    [[nodiscard]] bool contains(Entity e) const {
        const auto* first = std::get<0>(storages_);
        const uint32_t pos = first->find(e);
        return pos != StorageBase::kAbsent && pos < data_->size();
    }
    /// Position of `e` in the group's spans; requires contains(e).
    [[nodiscard]] size_t index_of(Entity e) const { return std::get<0>(storages_)->index_of(e); }
    /// The grouped entities, aligned with every span<T>().
    [[nodiscard]] std::span<const Entity> entities() const {
        return std::get<0>(storages_)->entities().first(data_->size());
    }
    /// The grouped components of owned type T, aligned with entities().
    template <class T>
    [[nodiscard]] std::span<T> span() const {
        return std::get<Storage<T>*>(storages_)->components().first(data_->size());
    }
    /// Calls fn(Entity, Ts&...) or fn(Ts&...) for each grouped entity in group order.
    template <class Fn>
    void each(Fn&& fn) const {
        const size_t n = data_->size();
        const std::span<const Entity> ents = entities();
        auto spans = std::make_tuple(span<Ts>()...);
        for (size_t i = 0; i < n; ++i) {
            if constexpr (std::is_invocable_v<Fn&, Entity, Ts&...>) {
                fn(ents[i], std::get<std::span<Ts>>(spans)[i]...);
            } else {
                fn(std::get<std::span<Ts>>(spans)[i]...);
            }
        }
    }
    /// Stable-sorts the group by `keys` (keys[i] is the key of group position i; size() entries)
    /// and permutes `keys` alongside so it stays aligned. Returns false, moving nothing, when the
    /// keys were already sorted; otherwise only the entities that change place are moved.
    bool sort_by_key(std::span<uint32_t> keys) { return data_->sort_by_key(keys); }
    /// Unstable, minimal-move variant of sort_by_key (see GroupData::partition_by_key): each key
    /// value still ends up as one contiguous range in ascending order.
    bool partition_by_key(std::span<uint32_t> keys) { return data_->partition_by_key(keys); }
    /// Stable-sorts the group with less(i, j) on group positions (read the spans inside `less`).
    template <class Less>
    bool sort(Less less) {
        return data_->sort(less);
    }
    /// The type-erased group state.
    [[nodiscard]] GroupData* data() const { return data_; }

private:
    GroupData* data_;
    std::tuple<Storage<Ts>*...> storages_;
};

}  // namespace aloha
