// Access: a system gets const spans of what it reads and mutable spans of what it writes, and the
// scheduler's plan is derived from the same declaration (the negative case is access_compile_fail.cpp).
#include "engine/scheduler/access.hpp"
#include "tests/engine/scheduler/test_phases.hpp"
#include "engine/scheduler/scheduler.hpp"

#include <gtest/gtest.h>

#include <type_traits>

namespace aloha {
namespace {

struct Position { float x = 0.0f; };
struct Speed { float v = 0.0f; };
struct Heat { float t = 0.0f; };
struct ClockTag {};  // host state declared by a tag

// A game's arrays as an access source.
struct Arrays {
    std::vector<Position> positions{{1.0f}, {2.0f}};
    std::vector<Speed> speeds{{0.0f}, {0.0f}};
    std::vector<Heat> heat{{5.0f}, {6.0f}};
    template <class T>
    std::span<T> span() {
        if constexpr (std::is_same_v<T, Position>) return positions;
        else if constexpr (std::is_same_v<T, Speed>) return speeds;
        else if constexpr (std::is_same_v<T, Heat>) return heat;
        else return {};
    }
};

using MoveAccess = Access<Reads<Position, ClockTag>, Writes<Speed>>;

TEST(Access, ReadsAreConstWritesAreMutableAndReachTheSource) {
    Arrays arrays;
    const MoveAccess a(arrays);
    static_assert(std::is_same_v<decltype(a.read<Position>()), std::span<const Position>>);
    static_assert(std::is_same_v<decltype(a.write<Speed>()), std::span<Speed>>);
    static_assert(std::is_same_v<decltype(a.read<Speed>()), std::span<const Speed>>);  // written implies readable
    ASSERT_EQ(a.read<Position>().size(), 2u);
    a.write<Speed>()[1].v = a.read<Position>()[1].x * 3.0f;
    EXPECT_EQ(arrays.speeds[1].v, 6.0f);
    EXPECT_EQ(a.read<Speed>()[1].v, 6.0f);
}

TEST(Access, DeclaredIdsAreTheScheduleAndThePlanFollowsThem) {
    EXPECT_EQ(MoveAccess::read_ids(), (std::vector<ComponentTypeId>{component_type_id<Position>(), component_type_id<ClockTag>()}));
    EXPECT_EQ(MoveAccess::write_ids(), std::vector<ComponentTypeId>{component_type_id<Speed>()});
    Arrays arrays;
    auto source = [&arrays]() -> Arrays& { return arrays; };
    using HeatAccess = Access<Reads<Speed>, Writes<Heat>>;        // reads what MoveAccess writes
    using ClockAccess = Access<Reads<>, Writes<Position, ClockTag>>;  // writes what MoveAccess reads
    Scheduler s(test::test_phases(), 1);
    int runs = 0;
    s.add(make_system<HeatAccess>("heat", test::TestPhase::Motion, source, [&](SystemContext&, const HeatAccess& a) {
        a.write<Heat>()[0].t += a.read<Speed>()[0].v;
        ++runs;
    }));
    s.add(make_system<MoveAccess>("move", test::TestPhase::Motion, source, [&](SystemContext&, const MoveAccess& a) {
        a.write<Speed>()[0].v = a.read<Position>()[0].x;
        ++runs;
    }));
    s.add(make_system<ClockAccess>("clock", test::TestPhase::Motion, source, [&](SystemContext&, const ClockAccess& a) {
        a.write<Position>()[0].x = 10.0f;
        ++runs;
    }));
    ASSERT_TRUE(s.build().ok());
    EXPECT_EQ(s.passes(), (std::vector<std::vector<std::string>>{{"clock"}, {"move"}, {"heat"}}));
    s.run_frame(0.1f);
    EXPECT_EQ(runs, 3);
    EXPECT_EQ(arrays.heat[0].t, 15.0f);  // 5 + the speed set from the position the clock wrote
}

}  // namespace
}  // namespace aloha
