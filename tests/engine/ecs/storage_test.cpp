// Storage<T>: sparse-set invariants, swap-and-pop removal, spans and paging.
#include <gtest/gtest.h>

#include <string>

#include "engine/ecs/registry.hpp"

namespace aloha {
namespace {

struct Name {
    std::string text;
};

TEST(Storage, DenseArraysStayAlignedUnderSwapAndPop) {
    Registry r;
    std::vector<Entity> es;
    for (int i = 0; i < 10; ++i) {
        es.push_back(r.create());
        r.emplace<Name>(es.back(), std::to_string(i));
    }
    Storage<Name>& s = r.storage<Name>();
    ASSERT_EQ(s.size(), 10u);
    ASSERT_TRUE(s.remove(es[2]));  // the last one (9) moves into position 2
    EXPECT_EQ(s.size(), 9u);
    EXPECT_EQ(s.entities()[2], es[9]);
    EXPECT_EQ(s.components()[2].text, "9");
    EXPECT_EQ(s.index_of(es[9]), 2u);
    EXPECT_FALSE(s.contains(es[2]));
    EXPECT_FALSE(s.remove(es[2]));
    for (size_t i = 0; i < s.size(); ++i) {
        const Entity e = s.entities()[i];
        EXPECT_EQ(s.index_of(e), i);
        EXPECT_EQ(&s.get(e), &s.components()[i]);
    }
}

TEST(Storage, EmplaceTwiceReplacesValue) {
    Registry r;
    const Entity e = r.create();
    r.emplace<Name>(e, "a");
    r.emplace<Name>(e, "b");
    EXPECT_EQ(r.storage<Name>().size(), 1u);
    EXPECT_EQ(r.get<Name>(e).text, "b");
}

TEST(Storage, SparseIndicesAcrossPages) {
    Registry r;
    std::vector<Entity> es;
    const uint32_t n = 3 * StorageBase::kPageSize + 17;  // spans four sparse pages
    for (uint32_t i = 0; i < n; ++i) es.push_back(r.create());
    for (uint32_t i = 0; i < n; i += 3) r.emplace<Name>(es[i], std::to_string(i));
    for (uint32_t i = 0; i < n; ++i) {
        ASSERT_EQ(r.has<Name>(es[i]), i % 3 == 0);
        if (i % 3 == 0) {
            ASSERT_EQ(r.get<Name>(es[i]).text, std::to_string(i));
        }
    }
}

TEST(Storage, DestroyRemovesFromEveryStorage) {
    Registry r;
    const Entity e = r.create();
    r.emplace<Name>(e, "x");
    r.emplace<int>(e, 5);
    r.destroy(e);
    EXPECT_EQ(r.storage<Name>().size(), 0u);
    EXPECT_EQ(r.storage<int>().size(), 0u);
}

}  // namespace
}  // namespace aloha
