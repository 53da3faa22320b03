// Motion controller on a crowd: 10,000 characters of the 64-joint humanoid playing a clip with
// update intervals 1, 2 and 4 (a third each), host arrays in a shuffled element order.
//  * CrowdUpdate/parallel:0 and :1: one frame of MotionController::update vs update_parallel
//    (TBB chunks of 64 due characters). Counters: posed (mean per frame), posed_spread (largest
//    minus smallest per-frame count over the run: 0 means throttled work is flat).
//  * ReachCrowd/dls10_else_ccd4:0 (CCD, 4 iterations) and :1 (DLS, 10): 1,000 characters holding
//    a reach (IK hooks, steady state with warm starts) on the test humanoid. Counter converged:
//    fraction within tolerance.
#include "systems/motion/controller.hpp"
#include "systems/motion/ik/ik_hooks.hpp"
#include "tests/systems/motion/ik/humanoid.hpp"
#include "tests/systems/motion/motion_test_util.hpp"

#include <benchmark/benchmark.h>

#include <algorithm>
#include <numeric>
#include <random>
#include <vector>

namespace aloha {
namespace {

void BM_CrowdUpdate(benchmark::State& state) {
    const bool parallel = state.range(0) != 0;
    const size_t n = 10000;
    const Skeleton sk = build_skeleton(test::make_humanoid64(), "humanoid64").value();
    ClipLibrary clips;
    const ClipId clip = clips.add(test::make_wave_clip(sk, 61, 2.0f), sk).value();
    MotionController mc(sk, clips, n);
    std::vector<uint32_t> element(n);
    std::iota(element.begin(), element.end(), 0u);
    std::mt19937 rng(3);
    std::shuffle(element.begin(), element.end(), rng);
    std::vector<AnimLod> lods(n);
    std::vector<MotionState> states(n);
    std::vector<Transform> xs(n);
    std::vector<Velocity> vs(n);
    const uint8_t intervals[3] = {1, 2, 4};
    for (size_t c = 0; c < n; ++c) {
        lods[element[c]].update_interval = intervals[c % 3];
        MotionRequest play;
        play.kind = RequestKind::PlayClip;
        play.clip = clip;
        play.start_time = static_cast<float>(c % 120) / 60.0f;
        play.crossfade_s = 0.0f;  // steady playback: no fade from the rest pose
        if (!mc.push_request(static_cast<uint32_t>(c), play)) state.SkipWithError("queue full");
    }
    MotionUpdateJob job{&mc, 1.0f / 60.0f, lods, states, xs, vs, element, parallel ? size_t{64} : size_t{0}};
    if (!job.Validate()) state.SkipWithError("invalid job");
    job.Run();  // requests start: everyone is posed once
    size_t lo = n, hi = 0, total = 0, frames = 0;
    for (auto _ : state) {
        const size_t posed = job.Run();
        lo = std::min(lo, posed);
        hi = std::max(hi, posed);
        total += posed;
        ++frames;
    }
    state.counters["posed"] = static_cast<double>(total) / static_cast<double>(std::max<size_t>(frames, 1));
    state.counters["posed_spread"] = static_cast<double>(hi - lo);
}
BENCHMARK(BM_CrowdUpdate)->Name("CrowdUpdate")->ArgName("parallel")->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_ReachCrowd(benchmark::State& state) {
    const bool dls = state.range(0) != 0;
    const size_t n = 1000;
    const Skeleton sk = test::make_humanoid(true);
    ClipLibrary clips;
    MotionController mc(sk, clips, n);
    IkHookContext ik;
    register_ik_hooks(mc, ik);
    std::vector<AnimLod> lods(n);
    std::vector<MotionState> states(n);
    std::vector<Transform> xs(n);
    std::vector<Velocity> vs(n);
    for (size_t c = 0; c < n; ++c) {
        lods[c].ik = dls ? IkSolver::Dls : IkSolver::Ccd;
        lods[c].ik_iterations = dls ? 10 : 4;
        MotionRequest r;
        r.kind = RequestKind::Reach;
        r.effector = static_cast<int16_t>(sk.find("RightWrist"));
        const float a = 0.3f * static_cast<float>(c % 10) / 10.0f;
        r.target = glm::vec3(-0.35f - 0.1f * a, 1.15f + a, 0.3f);
        if (!mc.push_request(static_cast<uint32_t>(c), r)) state.SkipWithError("queue full");
    }
    for (int f = 0; f < 30; ++f) mc.update(1.0f / 60.0f, lods, states, xs, vs);  // converge
    for (auto _ : state) benchmark::DoNotOptimize(mc.update(1.0f / 60.0f, lods, states, xs, vs));
    size_t converged = 0;
    for (const IkCharacterState& c : ik.characters) converged += c.last.converged ? 1 : 0;
    state.counters["characters"] = static_cast<double>(n);
    state.counters["converged"] = static_cast<double>(converged) / static_cast<double>(n);
}
BENCHMARK(BM_ReachCrowd)->Name("ReachCrowd")->ArgName("dls10_else_ccd4")->Arg(0)->Arg(1)->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace aloha

BENCHMARK_MAIN();
