// Storage<T>: sparse-set invariants, swap-and-pop removal, spans and paging.
#include <gtest/gtest.h>

#include <random>
#include <set>
#include <string>
#include <vector>

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

namespace aloha {
namespace {

struct Tag7 {
    int value = 0;
};

// Random create / emplace / remove / destroy with recycled indices: the sparse entries (dense
// position and generation) stay consistent with the dense array after every step, a stale handle to
// a recycled index is never found, and the view visits exactly the entities a plain set says it should.
TEST(Storage, SparseEntriesStayConsistentUnderRandomChurn) {
    Registry r;
    std::mt19937 rng(7);
    std::vector<Entity> live, dead;
    std::set<std::pair<uint32_t, uint32_t>> with_both;
    auto key = [](Entity e) { return std::make_pair(e.index, e.generation); };
    for (int step = 0; step < 20000; ++step) {
        const int op = static_cast<int>(rng() % 6);
        if (op <= 1 || live.empty()) {
            const Entity e = r.create();
            live.push_back(e);
            r.emplace<Name>(e, "n");
            if (rng() % 2) {
                r.emplace<Tag7>(e, Tag7{step});
                with_both.insert(key(e));
            }
        } else {
            const size_t i = rng() % live.size();
            const Entity e = live[i];
            if (op == 2) {
                r.storage<Tag7>().remove(e);
                with_both.erase(key(e));
            } else if (op == 3 && !r.storage<Tag7>().contains(e)) {
                r.emplace<Tag7>(e, Tag7{step});
                with_both.insert(key(e));
            } else {
                r.destroy(e);
                with_both.erase(key(e));
                live[i] = live.back();
                live.pop_back();
                dead.push_back(e);
            }
        }
        if (step % 1000 == 999) {
            ASSERT_TRUE(r.storage<Name>().consistent()) << "step " << step;
            ASSERT_TRUE(r.storage<Tag7>().consistent()) << "step " << step;
            for (const Entity d : dead) ASSERT_FALSE(r.storage<Name>().contains(d)) << "stale handle found";
            std::set<std::pair<uint32_t, uint32_t>> seen;
            r.view<Name, Tag7>().each([&](Entity e, Name&, Tag7&) { seen.insert(key(e)); });
            ASSERT_EQ(seen, with_both) << "step " << step;
        }
    }
}

}  // namespace
}  // namespace aloha
