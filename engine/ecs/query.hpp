// Query<Ts...>: a view that a system keeps across frames. It remembers where each matching entity's
// components sit in every storage and looks them up again only after a structural change.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <tuple>
#include <utility>

#include "engine/ecs/slot_table.hpp"
#include "engine/ecs/view.hpp"

namespace aloha {

/// Iterates the entities that have every component Ts (use `const T` for read-only access), like
/// View<Ts...>, but keeps the dense position of each match in every storage (a SlotTable) between
/// calls. Each call compares the storages' layout versions (StorageBase::layout_version) with the
/// ones the table was built at and rebuilds it only when an entity was added, removed or moved; a
/// call on unchanged storages reads the table front to back instead of the sparse pages, and
/// stretches where every storage holds the same entity at the same position are kept as ranges (no
/// table entries, no lookups). Component values may change freely without a rebuild.
/// Not for concurrent each() calls on one Query (a rebuild writes the table): give each system its
/// own. Structural changes to the storages while iterating are not allowed (use a CommandBuffer).
/// Registry::view() keeps such a table per list of component types itself (see ViewCache).
template <class... Ts>
class Query {
    static_assert(sizeof...(Ts) <= SlotTable::kMaxColumns, "too many component types for a slot table");
    static constexpr size_t kCount = sizeof...(Ts);

public:
    /// Builds a query over the given storages (they must outlive it); a null storage makes it empty.
    explicit Query(StorageFor<Ts>*... storages) : storages_(storages...) {}

    /// Calls fn(Entity, Ts&...) or fn(Ts&...) for each entity that has every Ts, in the dense order of
    /// the storage that was smallest when the table was built. Rebuilds the table first when stale.
    template <class Fn>
    void each(Fn&& fn) {
        refresh();
        if (missing()) return;
        const std::tuple<Ts*...> comps{std::get<StorageFor<Ts>*>(storages_)->components().data()...};
        table_.each(fn, comps);
    }
    /// Number of entities each() visits (rebuilds the table first when stale).
    [[nodiscard]] size_t count() {
        refresh();
        return table_.count();
    }
    /// How many times the slot table has been built (each structural change seen costs one build).
    [[nodiscard]] size_t rebuilds() const { return table_.rebuilds(); }
    /// Bytes the slot table holds (table entries and ranges).
    [[nodiscard]] size_t table_bytes() const { return table_.table_bytes(); }

private:
    // True when a storage is missing (the query is empty).
    [[nodiscard]] bool missing() const { return ((std::get<StorageFor<Ts>*>(storages_) == nullptr) || ...); }

    void refresh() {
        const std::array<uint64_t, kCount> versions{
            (std::get<StorageFor<Ts>*>(storages_) == nullptr ? uint64_t{0}
                                                             : std::get<StorageFor<Ts>*>(storages_)->layout_version())...};
        if (table_.current(versions)) return;
        if (missing()) {
            table_.build_empty(versions);
            return;
        }
        const std::array<const StorageBase*, kCount> bases{std::get<StorageFor<Ts>*>(storages_)...};
        table_.build(bases, versions);
    }

    std::tuple<StorageFor<Ts>*...> storages_;
    SlotTable table_;
};

}  // namespace aloha
