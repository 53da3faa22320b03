// Query<Ts...>: a view that a system keeps across frames. It remembers where each matching entity's
// components sit in every storage and looks them up again only after a structural change.
#pragma once

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <tuple>
#include <type_traits>
#include <utility>
#include <vector>

#include "engine/ecs/view.hpp"

namespace aloha {

/// Iterates the entities that have every component Ts (use `const T` for read-only access), like
/// View<Ts...>, but keeps the dense position of each match in every storage (a slot table) between
/// calls. Each call compares the storages' layout versions (StorageBase::layout_version) with the
/// ones the table was built at and rebuilds it only when an entity was added, removed or moved; a
/// call on unchanged storages reads the table front to back instead of the sparse pages, and
/// stretches where every storage holds the same entity at the same position are kept as ranges (no
/// table entries, no lookups). Component values may change freely without a rebuild.
/// Not for concurrent each() calls on one Query (a rebuild writes the table): give each system its
/// own. Structural changes to the storages while iterating are not allowed (use a CommandBuffer).
template <class... Ts>
class Query {
    static constexpr size_t kCount = sizeof...(Ts);

public:
    /// Builds a query over the given storages (they must outlive it); a null storage makes it empty.
    explicit Query(StorageFor<Ts>*... storages) : storages_(storages...) {}

    /// Calls fn(Entity, Ts&...) or fn(Ts&...) for each entity that has every Ts, in the dense order of
    /// the storage that was smallest when the table was built. Rebuilds the table first when stale.
    template <class Fn>
    void each(Fn&& fn) {
        refresh();
        run(fn, std::index_sequence_for<Ts...>{});
    }
    /// Number of entities each() visits (rebuilds the table first when stale).
    [[nodiscard]] size_t count() {
        refresh();
        size_t n = used_rows_;
        for (const Segment& s : segments_) n += s.aligned ? s.end - s.begin : 0;
        return n;
    }
    /// How many times the slot table has been built (each structural change seen costs one build).
    [[nodiscard]] size_t rebuilds() const { return rebuilds_; }
    /// Bytes the slot table holds (table entries and ranges).
    [[nodiscard]] size_t table_bytes() const {
        return rows_.size() * sizeof(uint32_t) + segments_.capacity() * sizeof(Segment);
    }

private:
    // Components read ahead of the one fn runs on, in table entries.
    static constexpr size_t kAhead = 16;
    // Shortest stretch of same-position entities kept as a range rather than as table entries.
    static constexpr uint32_t kMinRange = 32;

    // A piece of the iteration: driver positions [begin, end) where every storage holds the entity at
    // that same position (aligned), or table entries [begin, end) of rows_ (kCount positions each).
    struct Segment {
        uint32_t begin;
        uint32_t end;
        bool aligned;
    };

    template <class Fn, class... Cs>
    static void call(Fn& fn, Entity e, Cs&... components) {
        detail::call_each<Ts...>(fn, e, components...);
    }

    // True when the table matches the storages' current layout.
    [[nodiscard]] bool current() const { return built_ && versions_ == layout_versions(std::index_sequence_for<Ts...>{}); }
    template <size_t... Is>
    [[nodiscard]] std::array<uint64_t, kCount> layout_versions(std::index_sequence<Is...>) const {
        return {(std::get<Is>(storages_) == nullptr ? uint64_t{0} : std::get<Is>(storages_)->layout_version())...};
    }

    void refresh() {
        if (current()) return;
        used_rows_ = 0;
        segments_.clear();
        built_ = true;
        versions_ = layout_versions(std::index_sequence_for<Ts...>{});
        ++rebuilds_;
        if (((std::get<StorageFor<Ts>*>(storages_) == nullptr) || ...)) return;
        const std::array<size_t, kCount> sizes{std::get<StorageFor<Ts>*>(storages_)->size()...};
        size_t driver = 0;
        for (size_t i = 1; i < kCount; ++i) driver = sizes[i] < sizes[driver] ? i : driver;
        build(driver, std::index_sequence_for<Ts...>{});
    }

    // Walks the driving storage, looks every entity up in the others (index and generation) and records
    // matches: same-position stretches of at least kMinRange as ranges, the rest as table entries.
    template <size_t... Is>
    void build(size_t driver, std::index_sequence<Is...>) {
        const std::array<const StorageBase*, kCount> bases{std::get<Is>(storages_)...};
        const std::array<SparseIndex, kCount> sparse{std::get<Is>(storages_)->sparse()...};
        const std::span<const Entity> ents = bases[driver]->entities();
        const auto n = static_cast<uint32_t>(ents.size());
        // At most one entry per driver entity; grown (never shrunk) so rebuilds reuse the memory.
        if (rows_.size() < size_t(n) * kCount) rows_.resize(size_t(n) * kCount);
        uint32_t run_begin = 0;  // start of the current same-position stretch
        uint32_t run_end = 0;
        auto close_run = [&] {
            if (run_end - run_begin >= kMinRange) {
                segments_.push_back(Segment{run_begin, run_end, true});
            } else {
                for (uint32_t k = run_begin; k < run_end; ++k) append_row(std::array<uint32_t, kCount>{(void(Is), k)...});
            }
            run_begin = run_end;
        };
        std::array<uint32_t, kCount> row{};
        for (uint32_t k = 0; k < n; ++k) {
            if (k + kAhead < n) {
                for (size_t s = 0; s < kCount; ++s) {
                    if (s == driver) continue;
                    detail::prefetch<false>(sparse[s].position_slot(ents[k + kAhead].index));
                    detail::prefetch<false>(sparse[s].generation_slot(ents[k + kAhead].index));
                }
            }
            bool present = true;
            bool aligned = true;
            for (size_t s = 0; s < kCount; ++s) {
                row[s] = s == driver ? k : sparse[s].find(ents[k]);
                present &= row[s] != StorageBase::kAbsent;
                aligned &= row[s] == k;
            }
            if (aligned) {
                run_end = k + 1;  // extends the stretch (every path leaves run_end == k + 1)
                continue;
            }
            close_run();
            run_begin = run_end = k + 1;
            if (present) append_row(row);
        }
        close_run();
    }

    // Appends one table entry, opening a table segment when the last segment is a range.
    void append_row(const std::array<uint32_t, kCount>& row) {
        const auto at = static_cast<uint32_t>(used_rows_);
        if (segments_.empty() || segments_.back().aligned) segments_.push_back(Segment{at, at, false});
        std::copy(row.begin(), row.end(), rows_.begin() + std::ptrdiff_t(used_rows_ * kCount));
        ++used_rows_;
        ++segments_.back().end;
    }

    template <class Fn, size_t... Is>
    void run(Fn& fn, std::index_sequence<Is...>) {
        if (segments_.empty()) return;
        const std::tuple<decltype(std::get<Is>(storages_)->components().data())...> comps{
            std::get<Is>(storages_)->components().data()...};
        const Entity* ents = std::get<0>(storages_)->entities().data();
        for (const Segment& seg : segments_) {
            if (seg.aligned) {
                for (uint32_t k = seg.begin; k < seg.end; ++k) call(fn, ents[k], std::get<Is>(comps)[k]...);
                continue;
            }
            const uint32_t* row = rows_.data() + size_t(seg.begin) * kCount;
            const uint32_t* last = rows_.data() + size_t(seg.end) * kCount;
            const uint32_t* ahead_end = rows_.data() + used_rows_ * kCount;
            for (; row != last; row += kCount) {
                if (row + kAhead * kCount < ahead_end) {
                    (detail::prefetch<!std::is_const_v<Ts>>(std::get<Is>(comps) + row[kAhead * kCount + Is]), ...);
                }
                call(fn, ents[row[0]], std::get<Is>(comps)[row[Is]]...);
            }
        }
    }

    std::tuple<StorageFor<Ts>*...> storages_;
    std::vector<uint32_t> rows_;        // table entries: kCount dense positions per match
    size_t used_rows_ = 0;              // entries of rows_ in use
    std::vector<Segment> segments_;     // the iteration, in driver order
    std::array<uint64_t, kCount> versions_{};
    bool built_ = false;
    size_t rebuilds_ = 0;
};

}  // namespace aloha
