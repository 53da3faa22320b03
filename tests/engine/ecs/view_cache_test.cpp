// ViewCache behind Registry::view(): read only when the storages' layouts are the ones it was built at,
// built only once a layout has stayed put across two calls, the same entities in the same order as the
// stateless View after every kind of structural change, shared by const and non-const views of one
// type list, and safe when two threads call view() at once.
#include <gtest/gtest.h>

#include <atomic>
#include <cstdint>
#include <random>
#include <thread>
#include <vector>

#include "engine/ecs/registry.hpp"
#include "tests/engine/ecs/owned_components.hpp"

namespace aloha {
namespace {

using test::Owned;
using test::Tagged;

// The entities the registry's view visits, in order, each component checked against its owner.
std::vector<uint64_t> CachedVisits(Registry& r) {
    std::vector<uint64_t> seen;
    r.view<Owned, const Tagged>().each([&](Entity e, Owned& a, const Tagged& b) {
        EXPECT_EQ(a.owner, e.bits());
        EXPECT_EQ(b.owner, e.bits());
        seen.push_back(e.bits());
    });
    return seen;
}

// The same through a stateless view over the same storages (the reference).
std::vector<uint64_t> StatelessVisits(Registry& r) {
    std::vector<uint64_t> seen;
    View<Owned, const Tagged>(&r.storage<Owned>(), &r.storage<Tagged>()).each([&](Entity e, Owned&, const Tagged&) {
        seen.push_back(e.bits());
    });
    return seen;
}

// Creates `n` entities with Owned, every `every`-th one with Tagged too; returns them in creation order.
std::vector<Entity> Populate(Registry& r, int n, int every) {
    return test::PopulateOwned(r, n, [every](int i) { return i % every == 0; });
}

TEST(ViewCache, ReadOnlyWhenCurrentAndBuiltOnlyOnAStableLayout) {
    Registry r;
    const std::vector<Entity> es = Populate(r, 200, 3);
    const ViewCache* cache = r.view<Owned, const Tagged>().cache();
    ASSERT_NE(cache, nullptr);
    // First call: nothing recorded, the stateless loop runs and the layout is remembered.
    EXPECT_EQ(CachedVisits(r), StatelessVisits(r));
    EXPECT_EQ(cache->stateless_calls(), 1u);
    EXPECT_EQ(cache->builds(), 0u);
    // Second call on the same layout: built and read; later calls read it without building.
    for (int i = 0; i < 3; ++i) EXPECT_EQ(CachedVisits(r), StatelessVisits(r));
    EXPECT_EQ(cache->builds(), 1u);
    EXPECT_EQ(cache->table_calls(), 3u);
    // Changing values or an unrelated storage keeps the table.
    r.get<Owned>(es[0]).hits = 5;
    r.emplace<int>(es[1], 1);
    EXPECT_EQ(CachedVisits(r), StatelessVisits(r));
    EXPECT_EQ(cache->table_calls(), 4u);
    // A layout that changes before every call never gets the table (nor pays for a build).
    for (int i = 0; i < 5; ++i) {
        r.remove<Tagged>(es[size_t(3 * i)]);
        EXPECT_EQ(CachedVisits(r), StatelessVisits(r));
    }
    EXPECT_EQ(cache->stateless_calls(), 6u);
    EXPECT_EQ(cache->builds(), 1u);
    EXPECT_EQ(cache->table_calls(), 4u);
    // Once it stays put, the next call builds.
    EXPECT_EQ(CachedVisits(r), StatelessVisits(r));
    EXPECT_EQ(cache->builds(), 2u);
    // A view built from storages never touches the cache.
    const View<Owned> plain(&r.storage<Owned>());
    EXPECT_EQ(plain.cache(), nullptr);
    EXPECT_EQ(plain.count(), 200u);
}

TEST(ViewCache, MatchesTheStatelessViewUnderEveryStructuralChange) {
    Registry r;
    std::mt19937 rng(11);
    std::vector<Entity> alive = Populate(r, 300, 2);
    auto g = r.group<Owned, Tagged>();
    for (int step = 0; step < 300; ++step) {
        const int op = int(rng() % 7);
        if (op == 0) {  // add an entity
            const Entity e = r.create();
            alive.push_back(e);
            r.emplace<Owned>(e, Owned{e.bits(), 0});
            if (rng() % 2 != 0) r.emplace<Tagged>(e, e.bits());
        } else if (op == 1 && !alive.empty()) {  // destroy one
            const size_t i = rng() % alive.size();
            r.destroy(alive[i]);
            alive.erase(alive.begin() + std::ptrdiff_t(i));
        } else if (op == 2 && !alive.empty()) {  // remove or put back one component
            const Entity e = alive[rng() % alive.size()];
            if (r.has<Tagged>(e)) {
                r.remove<Tagged>(e);
            } else {
                r.emplace<Tagged>(e, e.bits());
            }
        } else if (op == 3 && r.storage<Owned>().size() > 1) {  // swap two positions of one storage
            const size_t n = r.storage<Owned>().size();
            r.storage<Owned>().swap_positions(rng() % n, rng() % n);
        } else if (op == 4) {  // reorder the group by a key
            std::vector<uint32_t> keys(g.size());
            for (uint32_t& k : keys) k = uint32_t(rng() % 4);
            g.sort_by_key(keys);
        }
        // ops 5, 6: no change, so the table gets built and read.
        const int calls = 1 + int(rng() % 3);
        for (int c = 0; c < calls; ++c) ASSERT_EQ(CachedVisits(r), StatelessVisits(r)) << "step " << step << " call " << c;
    }
    const ViewCache* cache = r.view<Owned, const Tagged>().cache();
    EXPECT_GT(cache->builds(), 10u);
    EXPECT_GT(cache->table_calls(), 10u);
}

TEST(ViewCache, NoStaleSlotIsReadAfterAStructuralChange) {
    Registry r;
    std::vector<Entity> es = Populate(r, 500, 1);
    const View<Owned, const Tagged> held = r.view<Owned, const Tagged>();
    EXPECT_EQ(held.count(), 500u);
    EXPECT_EQ(held.count(), 500u);  // built: 500 positions recorded
    ASSERT_EQ(held.cache()->builds(), 1u);
    // Shrink both storages far below the recorded positions (swap-and-pop moves the last ones down),
    // then call through the view taken before the change: a stale slot would reach past the end or
    // the wrong owner.
    for (size_t i = 0; i < 480; ++i) r.destroy(es[i]);
    int visited = 0;
    held.each([&](Entity e, Owned& a, const Tagged& b) {
        EXPECT_EQ(a.owner, e.bits());
        EXPECT_EQ(b.owner, e.bits());
        ++a.hits;
        ++visited;
    });
    EXPECT_EQ(visited, 20);
    EXPECT_EQ(held.cache()->builds(), 1u);  // the stateless loop ran
    EXPECT_EQ(held.count(), 20u);           // rebuilt at the new layout
    EXPECT_EQ(held.cache()->builds(), 2u);
    for (size_t i = 480; i < es.size(); ++i) EXPECT_EQ(r.get<Owned>(es[i]).hits, 1);
}

TEST(ViewCache, ConstAndNonConstViewsShareOneCachePerTypeList) {
    Registry r;
    const std::vector<Entity> es = Populate(r, 100, 4);
    const ViewCache* cache = r.view<Owned, const Tagged>().cache();
    EXPECT_EQ((r.view<const Owned, Tagged>().cache()), cache);
    EXPECT_EQ((r.view<Owned, Tagged>().cache()), cache);
    const Registry& cr = r;
    EXPECT_EQ((cr.view<Owned, Tagged>().cache()), cache);
    // Another order is another list (its iteration order is its own driver's).
    EXPECT_NE((r.view<Tagged, Owned>().cache()), cache);
    // Built by a const view, then written through a non-const one: each write reaches its owner.
    EXPECT_EQ((cr.view<Owned, Tagged>().count()), 25u);
    EXPECT_EQ((cr.view<Owned, Tagged>().count()), 25u);
    EXPECT_EQ(cache->builds(), 1u);
    r.view<Owned, const Tagged>().each([](Owned& a, const Tagged& b) {
        EXPECT_EQ(a.owner, b.owner);
        ++a.hits;
    });
    EXPECT_EQ(cache->builds(), 1u);
    for (size_t i = 0; i < es.size(); ++i) EXPECT_EQ(r.get<Owned>(es[i]).hits, i % 4 == 0 ? 1 : 0);
}

TEST(ViewCache, ConcurrentViewCallsAgreeAndBuildOncePerLayout) {
    Registry r;
    std::vector<Entity> es = Populate(r, 20000, 3);
    for (size_t i = 1; i < es.size(); i += 7) r.remove<Owned>(es[i]);  // scatter the layouts
    (void)r.view<const Owned, const Tagged>();  // storages and cache exist before the threads start
    constexpr int kRounds = 20;
    constexpr int kCallsPerThread = 3;
    std::atomic<int> failures{0};
    for (int round = 0; round < kRounds; ++round) {
        r.remove<Tagged>(es[size_t(3 * round)]);  // a new layout each round
        const std::vector<uint64_t> expected = StatelessVisits(r);
        std::atomic<int> ready{0};
        auto worker = [&] {
            ready.fetch_add(1);
            while (ready.load() < 2) {
            }
            for (int c = 0; c < kCallsPerThread; ++c) {
                std::vector<uint64_t> seen;
                seen.reserve(expected.size());
                r.view<const Owned, const Tagged>().each([&](Entity e, const Owned& a, const Tagged& b) {
                    if (a.owner != e.bits() || b.owner != e.bits()) failures.fetch_add(1);
                    seen.push_back(e.bits());
                });
                if (seen != expected) failures.fetch_add(1);
            }
        };
        std::thread a(worker);
        std::thread b(worker);
        a.join();
        b.join();
    }
    EXPECT_EQ(failures.load(), 0);
    // Per round: the first call runs stateless, the second builds, the other four read the table.
    const ViewCache* cache = r.view<const Owned, const Tagged>().cache();
    EXPECT_EQ(cache->stateless_calls(), size_t(kRounds));
    EXPECT_EQ(cache->builds(), size_t(kRounds));
    EXPECT_EQ(cache->table_calls(), size_t(kRounds * (2 * kCallsPerThread - 1)));
}

}  // namespace
}  // namespace aloha
