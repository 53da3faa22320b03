// Entity handles: generations, stale handles, and create/destroy churn against a reference model.
#include <gtest/gtest.h>

#include <cstdint>
#include <map>
#include <random>
#include <vector>

#include "engine/ecs/registry.hpp"

namespace aloha {
namespace {

struct Health {
    int value = 0;
};
struct Tag {
    uint32_t id = 0;
};

TEST(Entity, NullIsNeverValid) {
    Registry r;
    EXPECT_FALSE(r.valid(kNullEntity));
    const Entity e = r.create();
    EXPECT_TRUE(r.valid(e));
    EXPECT_NE(e, kNullEntity);
    EXPECT_EQ(r.try_get<Health>(kNullEntity), nullptr);
}

TEST(Entity, StaleHandleNeverReachesNewEntityData) {
    Registry r;
    const Entity old = r.create();
    r.emplace<Health>(old, 7);
    ASSERT_TRUE(r.destroy(old));
    const Entity reused = r.create();
    EXPECT_EQ(reused.index, old.index);  // LIFO reuse of the slot...
    EXPECT_NE(reused.generation, old.generation);  // ...with a new generation
    r.emplace<Health>(reused, 99);
    EXPECT_FALSE(r.valid(old));
    EXPECT_FALSE(r.has<Health>(old));
    EXPECT_EQ(r.try_get<Health>(old), nullptr);
    EXPECT_FALSE(r.destroy(old));  // destroying a stale handle is a no-op
    EXPECT_TRUE(r.valid(reused));
    EXPECT_EQ(r.get<Health>(reused).value, 99);
    EXPECT_FALSE(r.remove<Health>(old));
    EXPECT_TRUE(r.has<Health>(reused));
}

// Emplacing on a stale handle would store a second entry for the slot the live entity now holds: it
// aborts with a message in every build type (the assertion before it vanished in release builds).
TEST(EntityDeathTest, EmplaceOnAStaleHandleAbortsInEveryBuild) {
    Registry r;
    const Entity old = r.create();
    ASSERT_TRUE(r.destroy(old));
    const Entity reused = r.create();
    r.emplace<Health>(reused, 99);
    EXPECT_DEATH(r.emplace<Health>(old, 7), "Registry::emplace on a dead or stale entity");
    EXPECT_DEATH(r.emplace<Health>(kNullEntity, 7), "dead or stale");
    EXPECT_EQ(r.get<Health>(reused).value, 99);
}

TEST(Entity, GenerationIncrementsOnEveryReuse) {
    EntityPool pool;
    Entity e = pool.create();
    for (uint32_t i = 0; i < 1000; ++i) {
        const Entity next = (pool.destroy(e), pool.create());
        ASSERT_EQ(next.index, e.index);
        ASSERT_EQ(next.generation, e.generation + 1);
        e = next;
    }
    EXPECT_EQ(pool.alive(), 1u);
}

// 100k random operations on a registry and on a std::map reference model; every query must agree.
TEST(Entity, ChurnMatchesReferenceModel) {
    Registry r;
    std::mt19937 rng(12345);
    struct Model {
        bool has_health = false;
        int health = 0;
        bool has_tag = false;
        uint32_t tag = 0;
    };
    std::map<uint64_t, Model> live;  // keyed by Entity::bits()
    std::vector<Entity> handles;      // live and dead handles ever created
    for (int step = 0; step < 100000; ++step) {
        const uint32_t op = rng() % 8;
        if (op == 0 || handles.empty()) {
            const Entity e = r.create();
            ASSERT_EQ(live.count(e.bits()), 0u) << "a fresh handle equals an earlier one";
            live[e.bits()] = Model{};
            handles.push_back(e);
            continue;
        }
        const Entity e = handles[rng() % handles.size()];
        auto it = live.find(e.bits());
        const bool alive = it != live.end();
        ASSERT_EQ(r.valid(e), alive);
        switch (op) {
            case 1:
                ASSERT_EQ(r.destroy(e), alive);
                if (alive) live.erase(it);
                break;
            case 2:
            case 3:
                if (alive) {
                    const int v = static_cast<int>(rng() % 1000);
                    r.emplace<Health>(e, v);
                    it->second.has_health = true;
                    it->second.health = v;
                }
                break;
            case 4:
                if (alive) {
                    const uint32_t v = rng();
                    r.emplace<Tag>(e, v);
                    it->second.has_tag = true;
                    it->second.tag = v;
                }
                break;
            case 5:
                ASSERT_EQ(r.remove<Health>(e), alive && it->second.has_health);
                if (alive) it->second.has_health = false;
                break;
            case 6:
                ASSERT_EQ(r.remove<Tag>(e), alive && it->second.has_tag);
                if (alive) it->second.has_tag = false;
                break;
            default: {
                const Health* h = r.try_get<Health>(e);
                const Tag* t = r.try_get<Tag>(e);
                ASSERT_EQ(h != nullptr, alive && it->second.has_health);
                ASSERT_EQ(t != nullptr, alive && it->second.has_tag);
                if (h != nullptr) {
                    ASSERT_EQ(h->value, it->second.health);
                }
                if (t != nullptr) {
                    ASSERT_EQ(t->id, it->second.tag);
                }
                break;
            }
        }
        if (handles.size() > 4096) handles.erase(handles.begin(), handles.begin() + 2048);
    }
    ASSERT_EQ(r.alive(), live.size());
    size_t with_health = 0;
    for (const auto& [bits, m] : live) with_health += m.has_health ? 1 : 0;
    EXPECT_EQ(r.storage<Health>().size(), with_health);
    // Every stored component belongs to a live entity with the modelled value.
    const auto ents = r.storage<Health>().entities();
    const auto vals = r.storage<Health>().components();
    for (size_t i = 0; i < ents.size(); ++i) {
        auto it = live.find(ents[i].bits());
        ASSERT_NE(it, live.end());
        ASSERT_EQ(vals[i].value, it->second.health);
    }
}

TEST(Entity, ClearInvalidatesAllHandles) {
    Registry r;
    std::vector<Entity> es;
    for (int i = 0; i < 100; ++i) {
        es.push_back(r.create());
        r.emplace<Health>(es.back(), i);
    }
    r.clear();
    EXPECT_EQ(r.alive(), 0u);
    EXPECT_EQ(r.storage<Health>().size(), 0u);
    for (const Entity e : es) EXPECT_FALSE(r.valid(e));
    const Entity fresh = r.create();
    EXPECT_FALSE(r.has<Health>(fresh));
}

TEST(TypeId, DistinctStableAndNamed) {
    const ComponentTypeId a = component_type_id<Health>();
    const ComponentTypeId b = component_type_id<Tag>();
    EXPECT_NE(a, b);
    EXPECT_EQ(a, component_type_id<Health>());
    EXPECT_NE(type_name(a).find("Health"), std::string_view::npos);
    EXPECT_EQ(named_type_id("camera"), named_type_id("camera"));
    EXPECT_NE(named_type_id("camera"), named_type_id("pose pool"));
    EXPECT_EQ(type_name(named_type_id("pose pool")), "pose pool");
}

}  // namespace
}  // namespace aloha
