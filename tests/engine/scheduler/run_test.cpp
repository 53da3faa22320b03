// Scheduler::run_frame(): real concurrency, deterministic parallel_for, hooks, timings, commands.
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <cmath>
#include <cstring>
#include <latch>
#include <thread>

#include "engine/scheduler/scheduler.hpp"
#include "tests/engine/scheduler/test_phases.hpp"

namespace aloha {
namespace {

struct Left {};
struct Right {};
struct Counter {
    int n = 0;
};

// Waits until `latch` opens or a generous deadline passes (a guard against hanging, not a timing
// assertion): returns whether it opened.
bool WaitBounded(std::latch& latch) {
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(20);
    while (!latch.try_wait()) {
        if (std::chrono::steady_clock::now() > deadline) return false;
        std::this_thread::yield();
    }
    return true;
}

TEST(Run, SystemsOfOnePassRunConcurrentlyWithTwoThreads) {
    Scheduler s(test::test_phases(), 2);
    std::latch both(2);
    std::atomic<int> met{0};
    auto body = [&](SystemContext&) {
        both.count_down();
        // Only possible if the other system is running at the same time.
        if (WaitBounded(both)) met.fetch_add(1);
    };
    s.add(SystemDesc{"left", test::TestPhase::Motion, {}, writes<Left>(), body});
    s.add(SystemDesc{"right", test::TestPhase::Motion, {}, writes<Right>(), body});
    ASSERT_TRUE(s.build().ok());
    ASSERT_EQ(s.plan().size(), 1u);
    s.run_frame(0.016f);
    EXPECT_EQ(met.load(), 2);
    const auto trace = s.last_frame_trace();
    EXPECT_NE(trace[0].thread, trace[1].thread);
}

// Sum of sin(i) over 1e6 terms: per-chunk partial sums added in chunk order, so the float
// rounding sequence is fixed by (count, grain) alone and the bits must match for any thread count.
double ReduceWithThreads(unsigned threads, std::vector<double>& out_partials) {
    Scheduler s(test::test_phases(), threads);
    constexpr size_t kCount = 1'000'000;
    constexpr size_t kGrain = 4096;
    double result = 0;
    s.add(SystemDesc{"reduce", test::TestPhase::Attributes, {}, {}, [&](SystemContext& ctx) {
        std::vector<double> partial(SystemContext::chunk_count(kCount, kGrain), 0.0);
        ctx.parallel_for(kCount, kGrain, [&](size_t begin, size_t end) {
            double acc = 0;
            for (size_t i = begin; i < end; ++i) acc += std::sin(double(i) * 1e-3);
            partial[begin / kGrain] = acc;
        });
        double total = 0;
        for (const double p : partial) total += p;
        result = total;
        out_partials = partial;
    }});
    EXPECT_TRUE(s.build().ok());
    s.run_frame(0.0f);
    return result;
}

TEST(Run, ParallelForIsDeterministicAcrossThreadCounts) {
    std::vector<double> p1;
    std::vector<double> p2;
    const double one = ReduceWithThreads(1, p1);
    const double two = ReduceWithThreads(2, p2);
    EXPECT_EQ(std::memcmp(&one, &two, sizeof one), 0) << one << " vs " << two;
    ASSERT_EQ(p1.size(), 245u);  // ceil(1e6 / 4096)
    EXPECT_EQ(p1, p2);
    EXPECT_NE(one, 0.0);
}

TEST(Run, ParallelForCoversEveryIndexOnce) {
    Scheduler s(test::test_phases(), 2);
    std::vector<int> hits(10007, 0);
    s.add(SystemDesc{"cover", test::TestPhase::Skin, {}, {}, [&](SystemContext& ctx) {
        ctx.parallel_for(hits.size(), 100, [&](size_t b, size_t e) {
            for (size_t i = b; i < e; ++i) ++hits[i];
        });
        ctx.parallel_for(0, 100, [&](size_t, size_t) { ADD_FAILURE() << "empty range ran"; });
    }});
    ASSERT_TRUE(s.build().ok());
    s.run_frame(0.0f);
    for (const int h : hits) ASSERT_EQ(h, 1);
}

// The CPU total the World's frame budget steers: the latest run times of the systems before a phase.
TEST(Run, LatestTimeBeforeAPhaseSumsThoseSystemsOnly) {
    Scheduler s(test::test_phases(), 1);
    auto spin = [](SystemContext&) {
        const auto until = std::chrono::steady_clock::now() + std::chrono::microseconds(50);
        while (std::chrono::steady_clock::now() < until) {
        }
    };
    s.add(SystemDesc{"attributes", test::TestPhase::Attributes, {}, writes<Left>(), spin});
    s.add(SystemDesc{"motion", test::TestPhase::Motion, reads<Left>(), writes<Right>(), spin});
    s.add(SystemDesc{"render", test::TestPhase::Render, reads<Right>(), {}, spin});
    ASSERT_TRUE(s.build().ok());
    EXPECT_EQ(s.latest_ns_before(test::TestPhase::Render), 0u);  // nothing run yet
    for (int f = 0; f < 3; ++f) s.run_frame(0.1f);
    const uint64_t a = s.timings(0).latest(), m = s.timings(1).latest(), r = s.timings(2).latest();
    EXPECT_GE(r, 50'000u);  // the render system did run, and is left out below
    EXPECT_EQ(s.latest_ns_before(test::TestPhase::Render), a + m);
    EXPECT_EQ(s.latest_ns_before(test::TestPhase::Motion), a);
    EXPECT_EQ(s.latest_ns_before(test::TestPhase::Attributes), 0u);
}

TEST(Run, HookAfterEveryPhaseAndTimingsEveryFrame) {
    Scheduler s(test::test_phases(), 2);
    std::vector<Phase> seen;
    s.set_between_phases([&](Phase p) { seen.push_back(p); });
    std::vector<TraceEvent> sunk;
    s.set_trace_sink([&](const TraceEvent& e) { sunk.push_back(e); });
    std::vector<uint64_t> frames_seen;
    s.add(SystemDesc{"a", test::TestPhase::Attributes, {}, writes<Left>(), [&](SystemContext& ctx) {
        frames_seen.push_back(ctx.frame());
        EXPECT_FLOAT_EQ(ctx.dt(), 0.5f);
        EXPECT_EQ(ctx.system_name(), "a");
    }});
    s.add(SystemDesc{"b", test::TestPhase::Render, reads<Left>(), {}, [](SystemContext&) {}});
    s.add(SystemDesc{"c", test::TestPhase::Render, reads<Left>(), {}, [](SystemContext&) {}});
    ASSERT_TRUE(s.build().ok());
    constexpr int kFrames = 10;
    for (int f = 0; f < kFrames; ++f) s.run_frame(0.5f);
    ASSERT_EQ(seen.size(), test::kTestPhases.size() * kFrames);
    for (size_t i = 0; i < seen.size(); ++i) EXPECT_EQ(seen[i], test::kTestPhases[i % test::kTestPhases.size()]);
    EXPECT_EQ(frames_seen, (std::vector<uint64_t>{0, 1, 2, 3, 4, 5, 6, 7, 8, 9}));
    for (uint32_t i = 0; i < 3; ++i) {
        EXPECT_EQ(s.timings(i).size(), size_t(kFrames));
        EXPECT_EQ(s.timings(i).total_pushed(), uint64_t(kFrames));
        EXPECT_EQ(s.last_frame_trace()[i].frame, uint64_t(kFrames - 1));
        EXPECT_LE(s.last_frame_trace()[i].begin_ns, s.last_frame_trace()[i].end_ns);
    }
    ASSERT_NE(s.timings("b"), nullptr);
    EXPECT_EQ(s.timings("nope"), nullptr);
    EXPECT_EQ(s.frame_timings().size(), size_t(kFrames));
    ASSERT_EQ(sunk.size(), size_t(3 * kFrames));
    EXPECT_EQ(sunk[3].system, 0u);
    EXPECT_EQ(sunk[3].frame, 1u);
    // 'a' (Attributes) ends before 'b' (Render) starts in every frame.
    for (int f = 0; f < kFrames; ++f) EXPECT_LE(sunk[size_t(f) * 3].end_ns, sunk[size_t(f) * 3 + 1].begin_ns);
}

TEST(Run, PerSystemCommandBuffersApplyBetweenPhases) {
    Registry reg;
    Scheduler s(test::test_phases(), 2);
    s.set_between_phases([&](Phase) { s.apply_commands(reg); });
    s.add(SystemDesc{"spawner", test::TestPhase::Attributes, {}, writes<Counter>(), [](SystemContext& ctx) {
        const Entity e = ctx.commands().spawn();
        ctx.commands().add<Counter>(e, Counter{int(ctx.frame())});
    }});
    size_t counted = 0;
    s.add(SystemDesc{"counter", test::TestPhase::Rules, reads<Counter>(), {}, [&](SystemContext&) {
        counted = reg.storage<Counter>().size();
    }});
    ASSERT_TRUE(s.build().ok());
    s.run_frame(0.0f);
    EXPECT_EQ(counted, 1u);  // the spawn of Attributes is visible in Rules
    s.run_frame(0.0f);
    EXPECT_EQ(counted, 2u);
}

TEST(TimingRingTest, KeepsTheNewestValues) {
    TimingRing ring(4);
    for (uint64_t v = 1; v <= 6; ++v) ring.push(v);
    ASSERT_EQ(ring.size(), 4u);
    EXPECT_EQ(ring.at(0), 3u);
    EXPECT_EQ(ring.latest(), 6u);
    EXPECT_EQ(ring.total_pushed(), 6u);
    EXPECT_DOUBLE_EQ(ring.mean_ns(), 4.5);  // (3+4+5+6)/4, exact in double
}

}  // namespace
}  // namespace aloha
