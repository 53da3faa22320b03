// Motion benchmarks.
//  * BM_SampleLocalToModel: the ozz-animation comparison workload, exactly: a 64-joint humanoid-like
//    skeleton, a 2 s clip with 61 keys per joint for translation, rotation and scale, steady forward
//    playback in 1/60 s steps, 1,000 and 10,000 characters, one thread. The counter `per_joint` is
//    seconds per joint (sampling + local-to-model); ozz-animation 0.16 measured 24.8-28.2 ns here
//    (105,956 bytes per clip). The clip is build_clip's default, 16-bit quantised; `clip_bytes` is
//    its byte_size(). BM_SampleLocalToModelFloat32: the same with the lossless float clip.
//  * BM_SampleOnly / BM_SampleOnlyFloat32: the sampling half alone (no local-to-model), 1,000 characters.
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

// The comparison workload for `chars` characters: skeleton, clip, pose pool, per-character times
// spread over the clip and sampling caches.
struct Workload {
    Workload(size_t chars, ClipEncoding encoding)
        : sk(build_skeleton(test::make_humanoid64(), "humanoid64").value()),
          clip(build_clip(test::make_wave_clip(sk, 61, 2.0f), sk, encoding).value()),
          pool(sk.joint_count(), chars, &sk), times(chars), caches(chars) {
        for (size_t i = 0; i < chars; ++i) times[i] = static_cast<float>(i % 120) / 60.0f;
    }
    // Character i's time one 1/60 s step on, wrapped into the clip.
    float advance(size_t i) {
        float& t = times[i];
        t += 1.0f / 60.0f;
        if (t >= clip.duration()) t -= clip.duration();
        return t;
    }
    // Sets the counters: `per_joint` (seconds per joint per iteration), `joints`, `clip_bytes`.
    void count(benchmark::State& state) const {
        const double joints = static_cast<double>(times.size()) * sk.joint_count();
        state.counters["per_joint"] =
            benchmark::Counter(joints, benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
        state.counters["joints"] = joints;
        state.counters["clip_bytes"] = static_cast<double>(clip.byte_size());
    }
    Skeleton sk;
    AnimationClip clip;
    PosePool pool;
    std::vector<float> times;
    std::vector<SamplingCache> caches;
};

void sample_local_to_model(benchmark::State& state, ClipEncoding encoding) {
    const size_t chars = static_cast<size_t>(state.range(0));
    Workload w(chars, encoding);
    std::vector<uint32_t> slots(chars);
    std::iota(slots.begin(), slots.end(), 0u);
    AnimateBatchJob job{&w.clip, &w.sk, true, w.times, slots, w.caches, &w.pool};
    if (!job.Validate()) {
        state.SkipWithError("invalid job");
        return;
    }
    for (auto _ : state) {
        for (size_t i = 0; i < chars; ++i) w.advance(i);
        job.Run();
        benchmark::ClobberMemory();
    }
    w.count(state);
}
void BM_SampleLocalToModel(benchmark::State& state) { sample_local_to_model(state, ClipEncoding::Quantized16); }
void BM_SampleLocalToModelFloat32(benchmark::State& state) { sample_local_to_model(state, ClipEncoding::Float32); }
BENCHMARK(BM_SampleLocalToModel)->Arg(1000)->Arg(10000)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_SampleLocalToModelFloat32)->Arg(1000)->Arg(10000)->Unit(benchmark::kMicrosecond);

// Sampling alone: every character's local pose, no local-to-model (same workload).
void sample_only(benchmark::State& state, ClipEncoding encoding) {
    const size_t chars = static_cast<size_t>(state.range(0));
    Workload w(chars, encoding);
    for (auto _ : state) {
        for (size_t i = 0; i < chars; ++i) {
            const float t = w.advance(i);
            int k = 0;
            float alpha = 0.0f;
            find_key(w.clip, wrap_clip_time(t, w.clip.duration(), true), &w.caches[i], &k, &alpha);
            PoseView v = w.pool.view(i);
            sample_blocks(w.clip, k, alpha, v.translations.data(), v.rotations.data(), v.scales.data());
        }
        benchmark::ClobberMemory();
    }
    w.count(state);
}
void BM_SampleOnly(benchmark::State& state) { sample_only(state, ClipEncoding::Quantized16); }
void BM_SampleOnlyFloat32(benchmark::State& state) { sample_only(state, ClipEncoding::Float32); }
BENCHMARK(BM_SampleOnly)->Arg(1000)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_SampleOnlyFloat32)->Arg(1000)->Unit(benchmark::kMicrosecond);

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
