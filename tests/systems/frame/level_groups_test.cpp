// group_by_level: (type, level) grouping over a host's spans, in place or through `order`.
#include "systems/frame/level_groups.hpp"

#include <gtest/gtest.h>

namespace aloha {
namespace {

struct Crowd {
    std::vector<CharacterRef> refs;
    std::vector<GeomLod> geom;
    void add(uint16_t type, uint32_t id, uint8_t level) {
        refs.push_back({type, id});
        geom.emplace_back().level = level;
    }
};

TEST(LevelGroups, UnsortedElementsAreWalkedStablyThroughOrder) {
    Crowd c;
    c.add(1, 0, 2);  // element 0
    c.add(0, 0, 1);  // 1
    c.add(0, 1, 0);  // 2
    c.add(1, 1, 2);  // 3
    c.add(0, 2, 1);  // 4
    CharacterGroups g;
    group_by_level(c.refs, c.geom, g);
    EXPECT_FALSE(g.in_place());
    EXPECT_EQ(g.order, (std::vector<uint32_t>{2, 1, 4, 0, 3}));  // by key, ties in element order
    EXPECT_EQ(g.ids, (std::vector<uint32_t>{1, 0, 2, 0, 1}));
    ASSERT_EQ(g.ranges.size(), 3u);
    EXPECT_EQ(g.ranges[0].type, 0);
    EXPECT_EQ(g.ranges[0].level, 0);
    EXPECT_EQ(g.ranges[0].begin, 0u);
    EXPECT_EQ(g.ranges[0].end, 1u);
    EXPECT_EQ(g.ranges[1].level, 1);
    EXPECT_EQ(g.ranges[1].end - g.ranges[1].begin, 2u);
    EXPECT_EQ(g.ranges[2].type, 1);
    EXPECT_EQ(g.ranges[2].level, 2);
    EXPECT_EQ(g.ranges[2].end, 5u);
    EXPECT_EQ(g.keys[0], level_group_key(1, 2));
}

TEST(LevelGroups, SortedElementsAreGroupedInPlace) {
    Crowd c;
    c.add(0, 3, 0);
    c.add(0, 1, 0);
    c.add(0, 2, 4);
    c.add(2, 0, 1);
    CharacterGroups g;
    group_by_level(c.refs, c.geom, g);
    EXPECT_TRUE(g.in_place());
    EXPECT_EQ(g.order, (std::vector<uint32_t>{0, 1, 2, 3}));
    EXPECT_EQ(g.ids, (std::vector<uint32_t>{3, 1, 2, 0}));
    EXPECT_EQ(g.ranges.size(), 3u);
    // Regrouping after a level change reuses the same object.
    c.geom[0].level = 4;
    group_by_level(c.refs, c.geom, g);
    EXPECT_FALSE(g.in_place());
    EXPECT_EQ(g.order, (std::vector<uint32_t>{1, 0, 2, 3}));
}

TEST(LevelGroups, EmptyCrowdHasNoRanges) {
    CharacterGroups g;
    group_by_level({}, {}, g);
    EXPECT_EQ(g.size(), 0u);
    EXPECT_TRUE(g.ranges.empty());
}

}  // namespace
}  // namespace aloha
