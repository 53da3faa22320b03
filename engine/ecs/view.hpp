// View<Ts...>: iterates the entities that have every component Ts, driven by the smallest storage.
#pragma once

#include <algorithm>
#include <array>
#include <cassert>
#include <cstddef>
#include <cstdint>
#include <tuple>
#include <type_traits>
#include <utility>

#include "engine/ecs/slot_table.hpp"
#include "engine/ecs/storage.hpp"
#include "engine/ecs/view_cache.hpp"

namespace aloha {

/// The storage type a view element refers to: const storage for const components.
template <class T>
using StorageFor = std::conditional_t<std::is_const_v<T>, const Storage<std::remove_const_t<T>>,
                                      Storage<T>>;

namespace detail {

/// True when the `count` entities at `a` and `b` are equal (compiled to a few wide compares).
inline bool same_entities(const Entity* a, const Entity* b, size_t count) {
    uint64_t diff = 0;
    for (size_t k = 0; k < count; ++k) diff |= a[k].bits() ^ b[k].bits();
    return diff == 0;
}

}  // namespace detail

/// Non-owning view over the storages of Ts (use `const T` for read-only access).
/// A view from Registry::view() carries the registry's ViewCache for its type list: each() reads the
/// cache's slot table when the storages' layouts have not changed since the previous call (see
/// ViewCache for exactly when), and otherwise runs the stateless loop below, which looks every entity
/// up in the sparse pages. A view built from storages directly is always stateless. Both visit the
/// same entities in the same order: the dense order of the smallest storage (the first on ties).
/// Structural changes to the viewed storages while iterating are not allowed: record them in a
/// CommandBuffer and apply it afterwards.
/// The storages must hold live entities of one registry (Registry::emplace requires a live entity and
/// Registry::destroy removes every component), so an entity index is held by one generation in all of
/// them: each() then looks other storages up by index alone (4 bytes of sparse page per entity).
template <class... Ts>
class View {
    static_assert(sizeof...(Ts) > 0, "a view needs at least one component type");
    static_assert(sizeof...(Ts) <= SlotTable::kMaxColumns, "too many component types for a slot table");
    static constexpr size_t kCount = sizeof...(Ts);

public:
    /// Builds a view over the given storages; a null storage makes the view empty.
    explicit View(StorageFor<Ts>*... storages) : storages_(storages...) {}
    /// Builds a view that uses `cache` (kept over exactly these storages, none null), as
    /// Registry::view() does.
    View(ViewCache* cache, StorageFor<Ts>*... storages) : storages_(storages...), cache_(cache) {}

    /// Calls fn(Entity, Ts&...) or fn(Ts&...) for each entity that has every Ts, in the dense
    /// order of the smallest storage.
    template <class Fn>
    void each(Fn&& fn) const {
        if (cache_ != nullptr) {
            if (const SlotTable* table = cache_->acquire()) {
                const std::tuple<Ts*...> comps{std::get<StorageFor<Ts>*>(storages_)->components().data()...};
                table->each(fn, comps);
                return;
            }
        }
        const size_t driver = smallest();
        if (driver == kCount) return;
        dispatch(fn, driver, std::index_sequence_for<Ts...>{});
    }

    /// Number of entities the view visits (one each() call: for a cached view it counts as a call).
    [[nodiscard]] size_t count() const {
        size_t n = 0;
        each([&n](Entity, Ts&...) { ++n; });
        return n;
    }
    /// Upper bound on the number of entities visited: the smallest storage's size.
    [[nodiscard]] size_t size_hint() const {
        const size_t driver = smallest();
        return driver == kCount ? 0 : sizes()[driver];
    }
    /// True when `e` has every Ts.
    [[nodiscard]] bool contains(Entity e) const {
        return ((std::get<StorageFor<Ts>*>(storages_) != nullptr &&
                 std::get<StorageFor<Ts>*>(storages_)->contains(e)) && ...);
    }
    /// The registry's cache this view uses, or nullptr for a stateless view.
    [[nodiscard]] const ViewCache* cache() const { return cache_; }

private:
    // Entities checked per aligned-run step, and looked up per gather block.
    static constexpr size_t kRunStep = 8;
    static constexpr size_t kBlock = 64;
    // Longest aligned stretch compared before fn runs on it (its entities stay in L1 for fn).
    static constexpr size_t kRunChunk = 1024;
    // Dense positions of one block in each storage (row of the driver unused).
    using Slots = std::array<std::array<uint32_t, kBlock>, kCount>;

    // What the loop needs of one storage, read once per each().
    template <class T>
    struct Column {
        T* components;
        const Entity* entities;
        SparseIndex sparse;
    };

    // Sizes of the storages (0 for a missing one).
    [[nodiscard]] std::array<size_t, kCount> sizes() const {
        return sizes_of(std::index_sequence_for<Ts...>{});
    }
    template <size_t... Is>
    [[nodiscard]] std::array<size_t, kCount> sizes_of(std::index_sequence<Is...>) const {
        return {(std::get<Is>(storages_) == nullptr ? size_t{0} : std::get<Is>(storages_)->size())...};
    }
    // Position of the smallest storage (the first one on ties), or kCount when one is missing.
    [[nodiscard]] size_t smallest() const {
        if (((std::get<StorageFor<Ts>*>(storages_) == nullptr) || ...)) return kCount;
        const std::array<size_t, kCount> n = sizes();
        return static_cast<size_t>(std::min_element(n.begin(), n.end()) - n.begin());
    }

    template <class Fn, size_t... Is>
    void dispatch(Fn& fn, size_t driver, std::index_sequence<Is...>) const {
        // One loop per possible driver, so "is this the driving storage" is known at compile time.
        (void)((driver == Is ? (run<Is>(fn, std::index_sequence<Is...>{}), true) : false) || ...);
    }

    template <class Fn, class... Cs>
    static void call(Fn& fn, Entity e, Cs&... components) {
        detail::call_each<Ts...>(fn, e, components...);
    }

    // The loop, driven by storage D. Where every other storage holds the same entity at the same dense
    // position (components added in the same order) it runs straight over the arrays with no lookup.
    // Elsewhere it works in blocks, software-pipelined: while fn runs on one block, the next block's
    // dense positions are read from the sparse pages (prefetched a block earlier still) and its
    // components prefetched, so cache misses overlap instead of forming a chain per entity.
    template <size_t D, class Fn, size_t... Is>
    void run(Fn& fn, std::index_sequence<Is...>) const {
        const std::tuple<Column<Ts>...> cols{column<Is>()...};
        const Entity* ents = std::get<D>(cols).entities;
        const size_t n = std::get<D>(storages_)->size();
        std::array<Slots, 2> slots;
        size_t i = 0;
        while (i < n) {
            // Aligned stretch, compared kRunStep entities at a time, at most kRunChunk long.
            const size_t limit = std::min(n, i + kRunChunk);
            size_t j = i;
            while (j + kRunStep <= limit &&
                   ((Is == D || detail::same_entities(ents + j, std::get<Is>(cols).entities + j, kRunStep)) && ...)) {
                j += kRunStep;
            }
            while (j < limit && ((Is == D || ents[j] == std::get<Is>(cols).entities[j]) && ...)) ++j;
            if (j > i) {
                for (size_t k = i; k < j; ++k) call(fn, ents[k], std::get<Is>(cols).components[k]...);
                i = j;
                continue;
            }
            // Pipelined blocks until one turns out wholly aligned.
            size_t end = std::min(n, i + kBlock);
            resolve<D>(cols, ents, i, end, slots[0], std::index_sequence<Is...>{});
            size_t cur = 0;
            while (i < n) {
                const size_t next_end = std::min(n, end + kBlock);
                const size_t ahead = std::min(n, next_end + kBlock);
                for (size_t k = next_end; k < ahead; ++k) (prefetch_entry<Is, D>(cols, ents[k]), ...);
                const bool next_aligned = resolve<D>(cols, ents, end, next_end, slots[cur ^ 1], std::index_sequence<Is...>{});
                for (size_t k = i; k < end; ++k) {
                    const Slots& s = slots[cur];
                    if (((Is != D && s[Is][k - i] == StorageBase::kAbsent) || ...)) continue;
                    call(fn, ents[k], std::get<Is>(cols).components[Is == D ? k : s[Is][k - i]]...);
                }
                i = end;
                end = next_end;
                cur ^= 1;
                if (next_aligned) {
                    for (size_t k = i; k < end; ++k) call(fn, ents[k], std::get<Is>(cols).components[k]...);
                    i = end;
                    break;
                }
            }
        }
    }

    // Reads the dense positions of entities [begin, end) of the driver into `out` (row D unused) and
    // prefetches their components; true when every one sits at its own position in every storage.
    template <size_t D, class Cols, size_t... Is>
    static bool resolve(const Cols& cols, const Entity* ents, size_t begin, size_t end, Slots& out,
                        std::index_sequence<Is...>) {
        bool aligned = true;
        for (size_t k = begin; k < end; ++k) (lookup<Is, D>(cols, ents[k], k, out[Is][k - begin], aligned), ...);
        return aligned;
    }

    template <size_t I>
    [[nodiscard]] auto column() const {
        using T = std::tuple_element_t<I, std::tuple<Ts...>>;
        auto* s = std::get<I>(storages_);
        return Column<T>{s->components().data(), s->entities().data(), s->sparse()};
    }

    // Dense position of `e` (driver position `k`) in storage I (skipped for the driver), a prefetch of
    // its component, and `aligned` cleared unless that position is k. `e` is in the driving storage, so
    // (see the class comment) any entity storage I holds at e's index is `e` itself: the generation is
    // not read.
    template <size_t I, size_t D, class Cols>
    static void lookup(const Cols& cols, Entity e, size_t k, uint32_t& slot, bool& aligned) {
        if constexpr (I != D) {
            const auto& col = std::get<I>(cols);
            slot = col.sparse.position(e.index);
            assert((slot == StorageBase::kAbsent || col.entities[slot] == e) &&
                   "viewed storages hold different generations of one index (not one registry's live entities?)");
            aligned &= slot == k;
            using T = std::tuple_element_t<I, std::tuple<Ts...>>;
            detail::prefetch<!std::is_const_v<T>>(col.components + (slot == StorageBase::kAbsent ? 0 : slot));
        }
    }

    // Prefetches the dense position of `e` in storage I (skipped for the driver).
    template <size_t I, size_t D, class Cols>
    static void prefetch_entry(const Cols& cols, Entity e) {
        if constexpr (I != D) detail::prefetch<false>(std::get<I>(cols).sparse.position_slot(e.index));
    }

    std::tuple<StorageFor<Ts>*...> storages_;
    ViewCache* cache_ = nullptr;
};

}  // namespace aloha
