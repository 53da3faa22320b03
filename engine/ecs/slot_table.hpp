// SlotTable: where each entity matching a set of storages keeps its components (one dense position per
// storage), recorded once and read back on later passes until a storage's layout changes. The table
// behind Query and behind the registry's cached views; plus the small helpers every iteration loop shares.
#pragma once

#include <cassert>
#include <cstddef>
#include <cstdint>
#include <span>
#include <tuple>
#include <type_traits>
#include <utility>
#include <vector>

#include "engine/ecs/storage_base.hpp"

namespace aloha {

namespace detail {

/// Hints the cache to fetch `p` (for writing when `kWrite`); does nothing on other compilers.
template <bool kWrite>
inline void prefetch(const void* p) {
#if defined(__GNUC__) || defined(__clang__)
    __builtin_prefetch(p, kWrite ? 1 : 0, 3);
#else
    (void)p;
#endif
}

/// Calls fn(e, components...) when fn takes the entity first (as fn(Entity, Ts&...)), else fn(components...).
template <class... Ts, class Fn, class... Cs>
inline void call_each(Fn& fn, Entity e, Cs&... components) {
    if constexpr (std::is_invocable_v<Fn&, Entity, Ts&...>) {
        fn(e, components...);
    } else {
        fn(components...);
    }
}

}  // namespace detail

/// The matches of a list of storages (column c of the table is storage c) in the dense order of the
/// smallest storage (the first one on ties, as View drives), recorded at known layout versions
/// (StorageBase::layout_version). Stretches where every storage holds the same entity at the same
/// position are kept as ranges (no entries); every other match is one entry of one dense position per
/// storage. Not synchronised: the owner (Query, ViewCache) decides who may build and read it.
class SlotTable {
public:
    /// A piece of the iteration: driver positions [begin, end) where every storage holds the entity at
    /// that same position (aligned), or entries [begin, end) of the table.
    struct Segment {
        uint32_t begin;
        uint32_t end;
        bool aligned;
    };

    /// True when built at exactly `versions` (one per storage, in column order).
    [[nodiscard]] bool current(std::span<const uint64_t> versions) const;
    /// Most storages a table can have.
    static constexpr size_t kMaxColumns = 16;

    /// Records the matches of `storages` (non-null, one per column, at most kMaxColumns) whose layouts
    /// are at `versions`.
    void build(std::span<const StorageBase* const> storages, std::span<const uint64_t> versions);
    /// Records "nothing matches" at `versions` (a storage is missing).
    void build_empty(std::span<const uint64_t> versions);

    /// Number of matches recorded.
    [[nodiscard]] size_t count() const;
    /// How many times the table has been built.
    [[nodiscard]] size_t rebuilds() const { return rebuilds_; }
    /// Bytes the table holds (entries and ranges).
    [[nodiscard]] size_t table_bytes() const {
        return rows_.size() * sizeof(uint32_t) + segments_.capacity() * sizeof(Segment);
    }

    /// Calls fn(Entity, Cs&...) or fn(Cs&...) for every match, in the recorded order. `comps` are the
    /// component arrays of the storages (column order) the table was built over, at the versions it
    /// was built at; the entities are read from the driving storage, in its dense order.
    template <class... Cs, class Fn>
    void each(Fn& fn, const std::tuple<Cs*...>& comps) const {
        if (driver_storage_ == nullptr) return;  // built empty
        each_impl<Cs...>(fn, driver_storage_->entities().data(), comps, std::index_sequence_for<Cs...>{});
    }

private:
    // Components read ahead of the one fn runs on, in table entries.
    static constexpr size_t kAhead = 16;
    // Shortest stretch of same-position entities kept as a range rather than as entries.
    static constexpr uint32_t kMinRange = 32;

    template <class... Cs, class Fn, size_t... Is>
    void each_impl(Fn& fn, const Entity* ents, const std::tuple<Cs*...>& comps, std::index_sequence<Is...>) const {
        constexpr size_t kCols = sizeof...(Cs);
        assert(kCols == columns_);
        for (const Segment& seg : segments_) {
            if (seg.aligned) {
                for (uint32_t k = seg.begin; k < seg.end; ++k) detail::call_each<Cs...>(fn, ents[k], std::get<Is>(comps)[k]...);
                continue;
            }
            const uint32_t* row = rows_.data() + size_t(seg.begin) * kCols;
            const uint32_t* last = rows_.data() + size_t(seg.end) * kCols;
            const uint32_t* ahead_end = rows_.data() + used_rows_ * kCols;
            for (; row != last; row += kCols) {
                if (row + kAhead * kCols < ahead_end) {
                    (detail::prefetch<!std::is_const_v<Cs>>(std::get<Is>(comps) + row[kAhead * kCols + Is]), ...);
                }
                detail::call_each<Cs...>(fn, ents[row[driver_]], std::get<Is>(comps)[row[Is]]...);
            }
        }
    }

    // The build's walk for kCols columns (0: any number up to kMaxColumns), so the usual counts get
    // their per-entity loops unrolled.
    template <size_t kCols>
    void walk(std::span<const StorageBase* const> storages, size_t driver);
    // Appends one entry (`columns_` positions), opening a table segment when the last one is a range.
    template <size_t kCols>
    void append_row(const uint32_t* row);
    // Starts a build at `versions`: forgets the old matches.
    void reset(std::span<const uint64_t> versions);

    size_t columns_ = 0;
    size_t driver_ = 0;                            // column of the storage that drives the order
    const StorageBase* driver_storage_ = nullptr;  // that storage (null when built empty)
    std::vector<uint32_t> rows_;     // entries: columns_ dense positions per match
    size_t used_rows_ = 0;           // entries of rows_ in use
    std::vector<Segment> segments_;  // the iteration, in driver order
    std::vector<uint64_t> versions_;
    bool built_ = false;
    size_t rebuilds_ = 0;
};

}  // namespace aloha
