// CommandBuffer: recording during iteration, ordering, pending handles, dead targets.
#include <gtest/gtest.h>

#include <set>
#include <vector>

#include "engine/ecs/command_buffer.hpp"

namespace aloha {
namespace {

struct Pos {
    float x = 0;
};
struct Marked {
    int round = 0;
};

TEST(CommandBuffer, StructuralChangesDuringIterationAreDeferred) {
    Registry r;
    std::vector<Entity> es;
    for (int i = 0; i < 1000; ++i) {
        es.push_back(r.create());
        r.emplace<Pos>(es.back(), float(i));
    }
    CommandBuffer cmds;
    std::set<uint64_t> visited;
    size_t spawned = 0;
    r.view<Pos>().each([&](Entity e, Pos& p) {
        visited.insert(e.bits());
        const int i = static_cast<int>(p.x);
        if (i % 2 == 0) cmds.despawn(e);
        if (i % 3 == 0) cmds.add<Marked>(e, Marked{1});
        if (i % 5 == 0) cmds.remove<Pos>(e);
        if (i % 10 == 0) {
            const Entity child = cmds.spawn();
            cmds.add<Pos>(child, Pos{-1.0f});
            ++spawned;
        }
    });
    // Iteration saw exactly the original entities; nothing changed yet.
    EXPECT_EQ(visited.size(), 1000u);
    EXPECT_EQ(r.alive(), 1000u);
    EXPECT_EQ(r.storage<Pos>().size(), 1000u);
    // Marked on an entity despawned earlier in the buffer is skipped (i % 6 == 0: 167 of them,
    // plus remove<Pos> after despawn for i % 10 == 0: 100).
    const size_t skipped = cmds.apply(r);
    EXPECT_EQ(skipped, 167u + 100u);
    EXPECT_TRUE(cmds.empty());
    EXPECT_EQ(r.alive(), 500u + spawned);
    EXPECT_EQ(cmds.spawned().size(), spawned);
    for (int i = 0; i < 1000; ++i) {
        const Entity e = es[size_t(i)];
        EXPECT_EQ(r.valid(e), i % 2 != 0);
        if (i % 2 == 0) continue;
        EXPECT_EQ(r.has<Marked>(e), i % 3 == 0);
        EXPECT_EQ(r.has<Pos>(e), i % 5 != 0);
    }
    for (const Entity child : cmds.spawned()) {
        ASSERT_TRUE(r.valid(child));
        EXPECT_EQ(r.get<Pos>(child).x, -1.0f);
    }
}

TEST(CommandBuffer, AppliesInRecordingOrder) {
    Registry r;
    const Entity e = r.create();
    CommandBuffer cmds;
    cmds.add<Marked>(e, Marked{1});
    cmds.remove<Marked>(e);
    cmds.add<Marked>(e, Marked{3});
    EXPECT_EQ(cmds.size(), 3u);
    EXPECT_EQ(cmds.apply(r), 0u);
    EXPECT_EQ(r.get<Marked>(e).round, 3);
    // Spawn then despawn in the same buffer: the entity never survives, later commands skip.
    const Entity p = cmds.spawn();
    EXPECT_TRUE(CommandBuffer::is_pending(p));
    EXPECT_FALSE(r.valid(p));
    cmds.add<Pos>(p, Pos{1});
    cmds.despawn(p);
    cmds.add<Pos>(p, Pos{2});
    EXPECT_EQ(cmds.apply(r), 1u);
    EXPECT_EQ(r.alive(), 1u);
    EXPECT_EQ(r.storage<Pos>().size(), 0u);
}

TEST(CommandBuffer, ForeignPendingHandleAndClear) {
    Registry r;
    CommandBuffer a;
    CommandBuffer b;
    const Entity pa = a.spawn();
    b.add<Pos>(pa, Pos{1});  // pending handle of another buffer: no such spawn in b
    EXPECT_EQ(b.apply(r), 1u);
    a.clear();
    EXPECT_EQ(a.apply(r), 0u);
    EXPECT_EQ(r.alive(), 0u);
}

}  // namespace
}  // namespace aloha
