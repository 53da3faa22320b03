// SlotStore: paged per-level storage of the geometric controller (slot_store.hpp).
#include "systems/geometry/controller/slot_store.hpp"

#include <gtest/gtest.h>

#include <set>

namespace aloha {
namespace {

SlotLayout big_layout() {
    SlotLayout l;
    l.shapes = 53;
    l.muscle_vertices = 53 * 200;
    l.springs = 3000;
    l.spring_flags = 1;
    l.control = 3000;
    l.morph = 3000;
    l.control_normals = 3000;
    return l;
}

// Growing adds pages and never moves a record: a span taken before stays the slot's storage, with
// what was written through it.
TEST(SlotStore, GrowingKeepsEverySpanAndItsContents) {
    SlotStore store(big_layout());
    std::vector<uint32_t> slots;
    std::vector<glm::vec3*> first;
    for (uint32_t i = 0; i < 5 * store.slots_per_page() + 1; ++i) {
        const uint32_t s = store.acquire();
        const std::span<glm::vec3> p = store.positions(s);
        ASSERT_EQ(p.size(), 3000u);
        for (size_t k = 0; k < p.size(); ++k) p[k] = glm::vec3(float(s), float(k), 1.0f);
        slots.push_back(s);
        first.push_back(p.data());
    }
    EXPECT_EQ(store.capacity() % store.slots_per_page(), 0u);
    EXPECT_EQ(std::set<uint32_t>(slots.begin(), slots.end()).size(), slots.size());
    for (size_t i = 0; i < slots.size(); ++i) {
        const std::span<glm::vec3> p = store.positions(slots[i]);
        EXPECT_EQ(p.data(), first[i]);
        EXPECT_EQ(p[2999], glm::vec3(float(slots[i]), 2999.0f, 1.0f));
    }
}

// Buffers of one slot and of two slots never overlap (each record is laid out apart).
TEST(SlotStore, BuffersOfDistinctSlotsDoNotOverlap) {
    SlotStore store(big_layout());
    const uint32_t a = store.acquire(), b = store.acquire();
    auto range = [](auto span) {
        const auto* lo = reinterpret_cast<const std::byte*>(span.data());
        return std::pair(lo, lo + span.size_bytes());
    };
    std::vector<std::pair<const std::byte*, const std::byte*>> ranges;
    auto add = [&](auto... spans) { (ranges.push_back(range(spans)), ...); };
    for (const uint32_t s : {a, b})
        add(store.centres(s), store.rotations(s), store.radii(s), store.muscle_positions(s), store.muscle_normals(s),
            store.spring_end(s), store.spring_velocity(s), store.spring_prev_rest(s), store.spring_initialised(s),
            store.positions(s), store.deltas(s), store.normals(s));
    for (size_t i = 0; i < ranges.size(); ++i)
        for (size_t j = i + 1; j < ranges.size(); ++j)
            EXPECT_TRUE(ranges[i].second <= ranges[j].first || ranges[j].second <= ranges[i].first) << i << " " << j;
}

// Released slots are reused last-released first, with their flags cleared; capacity stays.
TEST(SlotStore, ReleasedSlotsAreReusedWithClearedFlags) {
    SlotStore store(big_layout());
    const uint32_t a = store.acquire();
    store.valid[a] = 1;
    store.pending[a] = 1;
    store.frames_left(a)[0] = 3;
    const uint32_t cap = store.capacity();
    store.release(a);
    EXPECT_EQ(store.acquire(), a);
    EXPECT_EQ(store.valid[a], 0);
    EXPECT_EQ(store.pending[a], 0);
    EXPECT_EQ(store.frames_left_of(a), 0);
    EXPECT_EQ(store.capacity(), cap);
    EXPECT_EQ(store.in_use(), 1u);
}

// Once the free slots run low a spare page is prepared (counted by spare_bytes), the next growth adds
// one page; reserve() rounds up to whole pages.
TEST(SlotStore, SparePageIsPreparedBeforeItIsNeeded) {
    SlotStore store(big_layout());
    EXPECT_EQ(store.spare_bytes(), 0u);
    const uint32_t page = store.slots_per_page();
    for (uint32_t i = 0; i < page; ++i) (void)store.acquire();
    EXPECT_EQ(store.capacity(), page);
    EXPECT_GT(store.spare_bytes(), 0u);
    (void)store.acquire();
    EXPECT_EQ(store.capacity(), 2 * page);
    SlotStore reserved(big_layout());
    reserved.reserve(page + 1);
    EXPECT_EQ(reserved.capacity(), 2 * page);
    EXPECT_EQ(reserved.in_use(), 0u);
}

// A layout with no buffers (hidden, impostor levels) still hands out slots with flags.
TEST(SlotStore, EmptyLayoutHandsOutSlots) {
    SlotStore store(SlotLayout{});
    std::set<uint32_t> seen;
    for (int i = 0; i < 3000; ++i) seen.insert(store.acquire());
    EXPECT_EQ(seen.size(), 3000u);
    EXPECT_TRUE(store.positions(*seen.begin()).empty());
}

}  // namespace
}  // namespace aloha
