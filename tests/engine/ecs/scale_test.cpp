// One million entities: create, add two components, iterate, destroy.
#include <gtest/gtest.h>

#include <vector>

#include "engine/ecs/registry.hpp"

namespace aloha {
namespace {

struct P {
    float x = 0;
};
struct V {
    float v = 0;
};

TEST(Scale, OneMillionEntities) {
    constexpr uint32_t kCount = 1'000'000;
    Registry r;
    r.reserve(kCount);
    r.storage<P>().reserve(kCount);
    r.storage<V>().reserve(kCount);
    std::vector<Entity> es;
    es.reserve(kCount);
    for (uint32_t i = 0; i < kCount; ++i) {
        const Entity e = r.create();
        r.emplace<P>(e, 0.0f);
        r.emplace<V>(e, float(i % 4));
        es.push_back(e);
    }
    EXPECT_EQ(r.alive(), kCount);
    r.view<P, const V>().each([](P& p, const V& v) { p.x += v.v * 0.5f; });
    // Exact: values are multiples of 0.5 below 2, representable in float.
    double sum = 0;
    for (const P& p : r.storage<P>().components()) sum += p.x;
    EXPECT_EQ(sum, (0.0 + 0.5 + 1.0 + 1.5) * (kCount / 4));
    auto g = r.group<P, V>();
    EXPECT_EQ(g.size(), kCount);
    for (uint32_t i = 0; i < kCount; i += 2) r.destroy(es[i]);
    EXPECT_EQ(r.alive(), kCount / 2);
    EXPECT_EQ(g.size(), kCount / 2);
    for (const Entity e : es) r.destroy(e);
    EXPECT_EQ(r.alive(), 0u);
    EXPECT_EQ(r.storage<P>().size(), 0u);
    EXPECT_EQ(g.size(), 0u);
}

}  // namespace
}  // namespace aloha
