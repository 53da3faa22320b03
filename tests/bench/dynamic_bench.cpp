// Cost of one dynamic-walk step (1/60 s) for one character (20 links, test humanoid).
#include "systems/motion/dynamic/dynamic_walk.hpp"
#include "tests/systems/motion/dynamic/walk_target.hpp"

#include <benchmark/benchmark.h>

namespace aloha {
namespace {

void BM_DynamicWalkStep(benchmark::State& state) {
    const Skeleton skel = test::make_humanoid(true);
    test::PoseBuffers out = test::rest_pose(skel);
    std::vector<glm::quat> target(out.r.size());
    test::WalkParams walk;
    const glm::vec3 root0 = test::walk_target(skel, 0.0f, walk, target);
    out.r = target;
    out.t[0] = root0;
    test::compute_model(skel, out);
    DynamicWalkSettings settings;
    settings.substeps = static_cast<int>(state.range(0));
    DynamicWalkState sim;
    if (!init_dynamic_walk(skel, out.cview(), glm::mat4(1.0f), sim, settings).ok()) {
        state.SkipWithError("init failed");
        return;
    }
    int i = 0;
    for (auto _ : state) {
        const glm::vec3 root = test::walk_target(skel, static_cast<float>(++i) / 60.0f, walk, target);
        step_dynamic_walk(skel, target, root, 1.0f / 60.0f, sim, out.view(), nullptr);
        benchmark::DoNotOptimize(out.m.data());
    }
    state.counters["bodies"] = static_cast<double>(sim.bodies.size());
}
BENCHMARK(BM_DynamicWalkStep)->Name("DynamicWalk/step/substeps")->Arg(2)->Arg(3)->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace aloha

BENCHMARK_MAIN();
