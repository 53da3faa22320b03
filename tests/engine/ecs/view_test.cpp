// View<Ts...>: visits exactly the entities having every component, const access, missing storages.
#include <gtest/gtest.h>

#include <set>

#include "engine/ecs/registry.hpp"

namespace aloha {
namespace {

struct Pos {
    float x = 0;
};
struct Vel {
    float v = 0;
};
struct Frozen {};
struct NeverUsed {
    int z = 0;
};

TEST(View, VisitsOnlyEntitiesWithAllComponents) {
    Registry r;
    std::set<uint64_t> expected;
    for (int i = 0; i < 100; ++i) {
        const Entity e = r.create();
        if (i % 2 == 0) r.emplace<Pos>(e, float(i));
        if (i % 3 == 0) r.emplace<Vel>(e, 1.0f);
        if (i % 2 == 0 && i % 3 == 0) expected.insert(e.bits());
    }
    std::set<uint64_t> seen;
    r.view<Pos, const Vel>().each([&](Entity e, Pos& p, const Vel& v) {
        EXPECT_TRUE(seen.insert(e.bits()).second) << "visited twice";
        p.x += v.v;
    });
    EXPECT_EQ(seen, expected);
    EXPECT_EQ((r.view<Pos, Vel>().count()), expected.size());
    // The smaller storage (Vel: 34 entities) drives the iteration.
    EXPECT_EQ((r.view<Pos, Vel>().size_hint()), r.storage<Vel>().size());
    for (const uint64_t bits : expected) {
        const Entity e{static_cast<uint32_t>(bits), static_cast<uint32_t>(bits >> 32)};
        EXPECT_EQ(r.get<Pos>(e).x, float(e.index) + 1.0f);  // exact: small integers in float
    }
}

TEST(View, ComponentsOnlyCallbackAndTagTypes) {
    Registry r;
    for (int i = 0; i < 10; ++i) {
        const Entity e = r.create();
        r.emplace<Pos>(e, 1.0f);
        if (i < 4) r.emplace<Frozen>(e);
    }
    int n = 0;
    r.view<Pos, Frozen>().each([&](Pos& p, Frozen&) {
        p.x = 0;
        ++n;
    });
    EXPECT_EQ(n, 4);
}

TEST(View, MissingComponentGivesEmptyView) {
    Registry r;
    for (int i = 0; i < 10; ++i) r.emplace<Pos>(r.create(), 1.0f);
    EXPECT_EQ((r.view<Pos, NeverUsed>().count()), 0u);
    const Registry& cr = r;
    // A const registry does not create storages: a never-created one makes the view empty.
    EXPECT_EQ((cr.view<Pos, Vel>().count()), 0u);
    EXPECT_EQ(cr.view<Pos>().count(), 10u);
    float sum = 0;
    cr.view<Pos>().each([&](const Pos& p) { sum += p.x; });
    EXPECT_EQ(sum, 10.0f);
}

}  // namespace
}  // namespace aloha
