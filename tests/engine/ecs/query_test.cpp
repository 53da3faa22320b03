// Query<Ts...>: visits exactly what View visits after every kind of structural change, rebuilds its
// slot table only when a storage's layout changed, and writes through to the right components.
#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <random>
#include <vector>

#include "engine/ecs/registry.hpp"
#include "tests/engine/ecs/owned_components.hpp"

namespace aloha {
namespace {

using test::Extra;
using test::Owned;
using test::Tagged;

// (entity bits) -> visits, by the query, with every component checked against its owner.
std::map<uint64_t, int> QueryVisits(Query<Owned, const Tagged>& q) {
    std::map<uint64_t, int> seen;
    q.each([&](Entity e, Owned& a, const Tagged& b) {
        EXPECT_EQ(a.owner, e.bits());
        EXPECT_EQ(b.owner, e.bits());
        ++seen[e.bits()];
    });
    return seen;
}

std::map<uint64_t, int> ViewVisits(Registry& r) {
    std::map<uint64_t, int> seen;
    r.view<Owned, const Tagged>().each([&](Entity e, Owned&, const Tagged&) { ++seen[e.bits()]; });
    return seen;
}

TEST(Query, MatchesTheViewUnderRandomStructuralChanges) {
    Registry r;
    auto q = r.query<Owned, const Tagged>();
    std::mt19937 rng(7);
    std::vector<Entity> alive;
    for (int step = 0; step < 400; ++step) {
        const int op = int(rng() % 6);
        if (op <= 1 || alive.empty()) {
            const Entity e = r.create();
            alive.push_back(e);
            if (rng() % 4 != 0) r.emplace<Owned>(e, Owned{e.bits(), 0});
            if (rng() % 2 != 0) r.emplace<Tagged>(e, e.bits());
        } else if (op == 2) {
            const size_t i = rng() % alive.size();
            r.destroy(alive[i]);
            alive.erase(alive.begin() + std::ptrdiff_t(i));
        } else if (op == 3) {
            const Entity e = alive[rng() % alive.size()];
            if (rng() % 2 == 0) {
                r.remove<Owned>(e);
            } else {
                r.remove<Tagged>(e);
            }
        } else if (op == 4) {
            const Entity e = alive[rng() % alive.size()];
            if (!r.has<Tagged>(e)) r.emplace<Tagged>(e, e.bits());
            if (!r.has<Owned>(e)) r.emplace<Owned>(e, Owned{e.bits(), 0});
        }
        // op 5: no structural change, the table is reused.
        const std::map<uint64_t, int> seen = QueryVisits(q);
        ASSERT_EQ(seen, ViewVisits(r)) << "step " << step;
        for (const auto& [bits, n] : seen) ASSERT_EQ(n, 1) << "visited twice";
        ASSERT_EQ(q.count(), seen.size());
    }
}

TEST(Query, RebuildsOnlyAfterALayoutChange) {
    Registry r;
    const std::vector<Entity> es = test::PopulateOwned(r, 100, [](int i) { return i % 3 == 0; });
    auto q = r.query<Owned, const Tagged>();
    EXPECT_EQ(q.count(), 34u);
    EXPECT_EQ(q.rebuilds(), 1u);
    // Writing component values, replacing a component in place and touching an unrelated storage
    // leave both layouts as they were.
    for (int i = 0; i < 5; ++i) QueryVisits(q);
    r.emplace<Tagged>(es[0], es[0].bits());
    r.emplace<Extra>(es[1], es[1].bits());
    EXPECT_EQ(q.count(), 34u);
    EXPECT_EQ(q.rebuilds(), 1u);
    // Each kind of layout change is seen once.
    r.emplace<Tagged>(es[1], es[1].bits());
    EXPECT_EQ(q.count(), 35u);
    EXPECT_EQ(q.rebuilds(), 2u);
    r.remove<Owned>(es[3]);
    EXPECT_EQ(q.count(), 34u);
    EXPECT_EQ(q.rebuilds(), 3u);
    r.destroy(es[6]);
    EXPECT_EQ(q.count(), 33u);
    EXPECT_EQ(q.rebuilds(), 4u);
    EXPECT_EQ(QueryVisits(q), ViewVisits(r));
    r.clear();
    EXPECT_EQ(q.count(), 0u);
    EXPECT_EQ(q.rebuilds(), 5u);
}

TEST(Query, FollowsAnOwningGroupsReordering) {
    Registry r;
    test::PopulateOwned(r, 300, [](int i) { return i % 2 == 0; });
    auto q = r.query<Owned, const Tagged>();
    EXPECT_EQ(QueryVisits(q), ViewVisits(r));
    // The group packs both storages (moving entities), then sorting by key moves them again.
    auto g = r.group<Owned, Tagged>();
    const size_t before = q.rebuilds();
    EXPECT_EQ(QueryVisits(q), ViewVisits(r));
    EXPECT_EQ(q.rebuilds(), before + 1);
    std::vector<uint32_t> keys(g.size());
    for (size_t i = 0; i < keys.size(); ++i) keys[i] = uint32_t((i * 7919) % 5);
    EXPECT_TRUE(g.sort_by_key(keys));
    EXPECT_EQ(QueryVisits(q), ViewVisits(r));
    EXPECT_EQ(q.rebuilds(), before + 2);
}

TEST(Query, WritesReachEachEntitysOwnComponent) {
    // Mixed layout: the first 200 entities have both components at the same positions (kept as a
    // range), then Tagged is added in reverse order for the next 200 (table entries).
    Registry r;
    const std::vector<Entity> es = test::PopulateOwned(r, 400, [](int i) { return i < 200; });
    for (int i = 399; i >= 200; --i) r.emplace<Tagged>(es[size_t(i)], es[size_t(i)].bits());
    auto q = r.query<Owned, const Tagged>();
    for (int round = 0; round < 3; ++round) {
        q.each([](Owned& a, const Tagged& b) {
            EXPECT_EQ(a.owner, b.owner);
            ++a.hits;
        });
    }
    for (const Entity e : es) EXPECT_EQ(r.get<Owned>(e).hits, 3);
    EXPECT_EQ(q.rebuilds(), 1u);
    EXPECT_GT(q.table_bytes(), 0u);
}

TEST(Query, MissingStorageGivesAnEmptyQuery) {
    Registry r;
    for (int i = 0; i < 10; ++i) r.emplace<Owned>(r.create(), Owned{});
    // The registry creates the missing storage empty: nothing matches until Tagged is added.
    auto q = r.query<Owned, const Tagged>();
    EXPECT_EQ(q.count(), 0u);
    const Entity e = r.create();
    r.emplace<Owned>(e, Owned{e.bits(), 0});
    r.emplace<Tagged>(e, e.bits());
    EXPECT_EQ(q.count(), 1u);
    Query<Owned, const Extra> none(&r.storage<Owned>(), nullptr);
    EXPECT_EQ(none.count(), 0u);
}

}  // namespace
}  // namespace aloha
