// Motion benchmarks.
//  * BM_SampleLocalToModel: the ozz-animation comparison workload, exactly: a 64-joint humanoid-like
//    skeleton, a 2 s clip with 61 keys per joint for translation, rotation and scale, steady forward
//    playback in 1/60 s steps, 1,000 and 10,000 characters, one thread. The counter `per_joint` is
//    seconds per joint (sampling + local-to-model); ozz-animation 0.16 measured 33-36 ns here.
//  * BM_ControllerRestingCrowd / BM_ControllerOneMoving: the motion pass with 10,000 resting + 1
//    moving character against 1 moving character alone (resting characters must cost ~nothing).
#include "systems/motion/controller.hpp"
#include "systems/motion/pose_pool.hpp"
#include "tests/systems/motion/motion_test_util.hpp"

#include <benchmark/benchmark.h>

#include <numeric>
#include <vector>

namespace aloha {
namespace {

void BM_SampleLocalToModel(benchmark::State& state) {
    const size_t chars = static_cast<size_t>(state.range(0));
    const Skeleton sk = build_skeleton(test::make_humanoid64(), "humanoid64").value();
    const AnimationClip clip = build_clip(test::make_wave_clip(sk, 61, 2.0f), sk).value();
    PosePool pool(sk.joint_count(), chars, &sk);
    std::vector<float> times(chars);
    for (size_t i = 0; i < chars; ++i) times[i] = static_cast<float>(i % 120) / 60.0f;  // spread over the clip
    std::vector<uint32_t> slots(chars);
    std::iota(slots.begin(), slots.end(), 0u);
    std::vector<SamplingCache> caches(chars);
    AnimateBatchJob job{&clip, &sk, true, times, slots, caches, &pool};
    if (!job.Validate()) {
        state.SkipWithError("invalid job");
        return;
    }
    for (auto _ : state) {
        for (float& t : times) {
            t += 1.0f / 60.0f;
            if (t >= clip.duration()) t -= clip.duration();
        }
        job.Run();
        benchmark::ClobberMemory();
    }
    state.counters["per_joint"] = benchmark::Counter(static_cast<double>(chars) * sk.joint_count(),
                                                     benchmark::Counter::kIsIterationInvariantRate |
                                                         benchmark::Counter::kInvert);
    state.counters["joints"] = static_cast<double>(chars) * sk.joint_count();
}
BENCHMARK(BM_SampleLocalToModel)->Arg(1000)->Arg(10000)->Unit(benchmark::kMicrosecond);

// Motion pass over `resting` characters at rest plus one playing the clip: resting characters are
// not in the active list, so this should cost about the same as BM_ControllerOneMoving.
void run_controller(benchmark::State& state, size_t resting) {
    const Skeleton sk = build_skeleton(test::make_humanoid64(), "humanoid64").value();
    ClipLibrary clips;
    const ClipId clip = clips.add(test::make_wave_clip(sk, 61, 2.0f), sk).value();
    const size_t n = resting + 1;
    MotionController mc(sk, clips, n);
    std::vector<AnimLod> lods(n);
    std::vector<MotionState> states(n);
    std::vector<Transform> xs(n);
    std::vector<Velocity> vs(n);
    MotionRequest play;
    play.kind = RequestKind::PlayClip;
    play.clip = clip;
    if (!mc.push_request(static_cast<uint32_t>(n / 2), play)) state.SkipWithError("queue full");
    MotionUpdateJob job{&mc, 1.0f / 60.0f, lods, states, xs, vs};
    if (!job.Validate()) state.SkipWithError("invalid job");
    for (auto _ : state) benchmark::DoNotOptimize(job.Run());
    state.counters["characters"] = static_cast<double>(n);
}
void BM_ControllerRestingCrowd(benchmark::State& state) { run_controller(state, 10000); }
void BM_ControllerOneMoving(benchmark::State& state) { run_controller(state, 0); }
BENCHMARK(BM_ControllerRestingCrowd)->Unit(benchmark::kNanosecond);
BENCHMARK(BM_ControllerOneMoving)->Unit(benchmark::kNanosecond);

}  // namespace
}  // namespace aloha

BENCHMARK_MAIN();
