// Owning groups: alignment invariants under random structural changes, sorting, key ranges.
#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <random>
#include <vector>

#include "engine/ecs/command_buffer.hpp"
#include "engine/ecs/registry.hpp"

namespace aloha {
namespace {

// Each component remembers its owner so alignment can be checked value by value.
struct A {
    uint64_t owner = 0;
};
struct B {
    uint64_t owner = 0;
    uint32_t level = 0;
};
struct C {
    int unused = 0;
};

// Checks: size == number of entities with A and B; positions [0,size) hold the same entity in
// both storages and in entities(); each component at i belongs to that entity.
void ExpectAligned(Registry& r, const Group<A, B>& g) {
    size_t complete = 0;
    for (const Entity e : r.storage<A>().entities()) complete += r.has<B>(e) ? 1 : 0;
    ASSERT_EQ(g.size(), complete);
    const auto ents = g.entities();
    const auto as = g.span<A>();
    const auto bs = g.span<B>();
    ASSERT_EQ(as.size(), g.size());
    ASSERT_EQ(bs.size(), g.size());
    for (size_t i = 0; i < g.size(); ++i) {
        ASSERT_EQ(r.storage<A>().entities()[i], ents[i]);
        ASSERT_EQ(r.storage<B>().entities()[i], ents[i]);
        ASSERT_EQ(as[i].owner, ents[i].bits());
        ASSERT_EQ(bs[i].owner, ents[i].bits());
        ASSERT_TRUE(g.contains(ents[i]));
    }
    // Nobody past the group range is complete.
    for (size_t i = g.size(); i < r.storage<A>().size(); ++i) {
        ASSERT_FALSE(r.has<B>(r.storage<A>().entities()[i]));
    }
}

TEST(Group, PacksExistingEntitiesOnCreation) {
    Registry r;
    for (int i = 0; i < 50; ++i) {
        const Entity e = r.create();
        r.emplace<A>(e, e.bits());
        if (i % 3 != 0) r.emplace<B>(e, e.bits(), 0u);
    }
    const Group<A, B> g = r.group<A, B>();
    EXPECT_EQ(g.size(), 33u);  // i % 3 != 0 for 33 of 0..49
    ExpectAligned(r, g);
    // Asking again returns the same group (in any type order).
    EXPECT_EQ((r.group<B, A>().data()), g.data());
}

TEST(Group, AlignmentSurvivesRandomChangesAndSorts) {
    Registry r;
    Group<A, B> g = r.group<A, B>();
    std::mt19937 rng(7);
    std::vector<Entity> live;
    CommandBuffer cmds;
    std::vector<uint32_t> keys;
    for (int step = 0; step < 20000; ++step) {
        const uint32_t op = rng() % 10;
        if (op < 3 || live.empty()) {
            const Entity e = r.create();
            live.push_back(e);
            if (rng() % 2) r.emplace<A>(e, e.bits());
            if (rng() % 2) r.emplace<B>(e, e.bits(), uint32_t(rng() % 4));
            continue;
        }
        const size_t k = rng() % live.size();
        const Entity e = live[k];
        switch (op) {
            case 3: r.emplace<A>(e, e.bits()); break;
            case 4: r.emplace<B>(e, e.bits(), uint32_t(rng() % 4)); break;
            case 5: r.remove<A>(e); break;
            case 6: r.remove<B>(e); break;
            case 7:
                r.destroy(e);
                live[k] = live.back();
                live.pop_back();
                break;
            case 8:  // the same through the command buffer
                if (rng() % 2) cmds.add<B>(e, B{e.bits(), uint32_t(rng() % 4)}); else cmds.remove<A>(e);
                if (rng() % 8 == 0) cmds.apply(r);
                break;
            default: {
                keys.resize(g.size());
                const auto bs = g.span<B>();
                for (size_t i = 0; i < keys.size(); ++i) keys[i] = bs[i].level;
                g.sort_by_key(keys);
                ASSERT_TRUE(std::is_sorted(keys.begin(), keys.end()));
                for (size_t i = 0; i < keys.size(); ++i) ASSERT_EQ(g.span<B>()[i].level, keys[i]);
                break;
            }
        }
        if (step % 500 == 0) ExpectAligned(r, g);
    }
    cmds.apply(r);
    ExpectAligned(r, g);
}

TEST(Group, SortByKeyIsStableAndGivesRanges) {
    Registry r;
    Group<A, B> g = r.group<A, B>();
    std::vector<Entity> order;
    const uint32_t levels[] = {2, 0, 1, 2, 0, 0, 3, 1, 2, 0};
    for (const uint32_t lv : levels) {
        const Entity e = r.create();
        r.emplace<A>(e, e.bits());
        r.emplace<B>(e, e.bits(), lv);
        order.push_back(e);
    }
    std::vector<uint32_t> keys(levels, levels + 10);
    EXPECT_TRUE(g.sort_by_key(keys));
    EXPECT_EQ(keys, (std::vector<uint32_t>{0, 0, 0, 0, 1, 1, 2, 2, 2, 3}));
    // Stable: within a level the original insertion order is kept.
    std::vector<Entity> expected;
    for (uint32_t lv = 0; lv < 4; ++lv) {
        for (size_t i = 0; i < 10; ++i) {
            if (levels[i] == lv) expected.push_back(order[i]);
        }
    }
    EXPECT_TRUE(std::equal(expected.begin(), expected.end(), g.entities().begin()));
    ExpectAligned(r, g);
    const std::vector<KeyRange> ranges = key_ranges(keys);
    ASSERT_EQ(ranges.size(), 4u);
    const size_t begins[] = {0, 4, 6, 9};
    const size_t ends[] = {4, 6, 9, 10};
    for (uint32_t i = 0; i < 4; ++i) {
        EXPECT_EQ(ranges[i].key, i);
        EXPECT_EQ(ranges[i].begin, begins[i]);
        EXPECT_EQ(ranges[i].end, ends[i]);
        for (size_t p = ranges[i].begin; p < ranges[i].end; ++p) EXPECT_EQ(g.span<B>()[p].level, i);
    }
    // Already sorted: the cheap path moves nothing and reports it.
    EXPECT_FALSE(g.sort_by_key(keys));
    // Large keys take the comparison-sort path; result must match std::stable_sort.
    std::vector<uint32_t> big(g.size());
    for (size_t i = 0; i < big.size(); ++i) big[i] = (i % 3) * 100000u;
    std::vector<uint32_t> ref = big;
    std::stable_sort(ref.begin(), ref.end());
    g.sort_by_key(big);
    EXPECT_EQ(big, ref);
    ExpectAligned(r, g);
}

TEST(Group, PartitionByKeyMovesOnlyMisplacedEntities) {
    Registry r;
    Group<A, B> g = r.group<A, B>();
    std::mt19937 rng(11);
    for (int i = 0; i < 5000; ++i) {
        const Entity e = r.create();
        r.emplace<A>(e, e.bits());
        r.emplace<B>(e, e.bits(), uint32_t(rng() % 5));
    }
    std::vector<uint32_t> keys(g.size());
    for (size_t i = 0; i < keys.size(); ++i) keys[i] = g.span<B>()[i].level;
    EXPECT_TRUE(g.partition_by_key(keys));
    ASSERT_TRUE(std::is_sorted(keys.begin(), keys.end()));
    ExpectAligned(r, g);
    // Change 1% of the levels, then re-partition: an entity whose key still matches the bucket
    // it sits in must not move.
    for (int k = 0; k < 50; ++k) {
        const size_t i = rng() % keys.size();
        keys[i] = uint32_t(rng() % 5);
        g.span<B>()[i].level = keys[i];
    }
    std::vector<uint32_t> bucket_of_position(keys.size());
    {
        std::vector<uint32_t> sorted = keys;
        std::sort(sorted.begin(), sorted.end());
        bucket_of_position = sorted;  // key that position i must hold after partitioning
    }
    const std::vector<Entity> before(g.entities().begin(), g.entities().end());
    const std::vector<uint32_t> old_keys = keys;
    g.partition_by_key(keys);
    ASSERT_TRUE(std::is_sorted(keys.begin(), keys.end()));
    size_t moved = 0;
    for (size_t i = 0; i < keys.size(); ++i) {
        if (old_keys[i] == bucket_of_position[i]) {
            EXPECT_EQ(g.entities()[i], before[i]) << "a well-placed entity moved at " << i;
        }
        moved += g.entities()[i] == before[i] ? 0 : 1;
        EXPECT_EQ(g.span<B>()[i].level, keys[i]);
    }
    EXPECT_LE(moved, 2u * 50u);  // each changed key displaces at most itself and one other
    ExpectAligned(r, g);
}

TEST(Group, SortWithComparator) {
    Registry r;
    Group<A, B> g = r.group<A, B>();
    for (uint32_t i = 0; i < 20; ++i) {
        const Entity e = r.create();
        r.emplace<A>(e, e.bits());
        r.emplace<B>(e, e.bits(), (i * 7) % 5);
    }
    const auto bs = g.span<B>();
    g.sort([&](size_t i, size_t j) { return bs[i].level > bs[j].level; });  // descending
    for (size_t i = 1; i < g.size(); ++i) EXPECT_GE(g.span<B>()[i - 1].level, g.span<B>()[i].level);
    ExpectAligned(r, g);
}

TEST(Group, NonOwnedComponentsDoNotDisturb) {
    Registry r;
    Group<A, B> g = r.group<A, B>();
    const Entity e = r.create();
    r.emplace<A>(e, e.bits());
    r.emplace<C>(e);
    EXPECT_EQ(g.size(), 0u);
    r.emplace<B>(e, e.bits(), 1u);
    EXPECT_EQ(g.size(), 1u);
    r.remove<C>(e);
    EXPECT_EQ(g.size(), 1u);
    r.storage<B>().clear();
    EXPECT_EQ(g.size(), 0u);
    ExpectAligned(r, g);
}

}  // namespace
}  // namespace aloha

namespace aloha {
namespace {

TEST(GroupDeathTest, OverlappingGroupsAbortNamingTheType) {
    GTEST_FLAG_SET(death_test_style, "threadsafe");
    auto overlap = [] {
        Registry r;
        (void)r.group<A, B>();
        (void)r.group<A, C>();  // A is already packed by group<A, B>
    };
    EXPECT_DEATH(overlap(), "already owned by another group");
}

}  // namespace
}  // namespace aloha
