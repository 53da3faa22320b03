// Scheduler overhead per frame (empty systems, including timing and trace bookkeeping) and the
// cost of a deterministic parallel_for over a light workload.
#include <benchmark/benchmark.h>

#include <cmath>
#include <string>
#include <vector>

#include "engine/scheduler/scheduler.hpp"
#include "tests/engine/scheduler/test_phases.hpp"

namespace {

template <int N>
struct Slot {};

// Seven phases x range(0) independent systems each (one pass per phase).
void BM_EmptyFrame(benchmark::State& state) {
    aloha::Scheduler s(aloha::test::test_phases(), unsigned(state.range(1)));
    const std::vector<aloha::ComponentTypeId> none;
    int k = 0;
    for (const aloha::Phase p : aloha::test::kTestPhases) {
        for (int64_t i = 0; i < state.range(0); ++i) {
            s.add(aloha::SystemDesc{"s" + std::to_string(k++), p, {},
                                    {aloha::named_type_id("slot" + std::to_string(i))},
                                    [](aloha::SystemContext&) {}});
        }
    }
    if (!s.build().ok()) state.SkipWithError("build failed");
    for (auto _ : state) s.run_frame(0.016f);
    state.counters["systems"] = double(s.system_count());
    state.counters["ns_per_system"] = benchmark::Counter(
        double(s.system_count()), benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}

void BM_ParallelFor(benchmark::State& state) {
    aloha::Scheduler s(aloha::test::test_phases(), unsigned(state.range(1)));
    std::vector<float> data(size_t(state.range(0)), 1.0f);
    s.add(aloha::SystemDesc{"work", aloha::test::TestPhase::Motion, {}, {}, [&](aloha::SystemContext& ctx) {
        ctx.parallel_for(data.size(), 4096, [&](size_t b, size_t e) {
            for (size_t i = b; i < e; ++i) data[i] = std::sqrt(data[i] * 1.0001f + 0.5f);
        });
    }});
    if (!s.build().ok()) state.SkipWithError("build failed");
    for (auto _ : state) s.run_frame(0.016f);
    state.SetItemsProcessed(int64_t(state.iterations()) * state.range(0));
}

}  // namespace

BENCHMARK(BM_EmptyFrame)->Args({1, 1})->Args({1, 2})->Args({4, 2});
BENCHMARK(BM_ParallelFor)->Args({1'000'000, 1})->Args({1'000'000, 2});
BENCHMARK_MAIN();
