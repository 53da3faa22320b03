// Time per IK solve (CCD, DLS) on the test humanoid's arm and leg reaches, and error-vs-iteration
// curves for both written to $ALOHA_IK_CSV (default ./ik_convergence.csv).
#include "systems/motion/ik/ccd.hpp"
#include "systems/motion/ik/dls.hpp"
#include "tests/systems/motion/ik/ik_test_util.hpp"

#include <benchmark/benchmark.h>

#include <cstdio>
#include <cstdlib>

namespace aloha {
namespace {

struct Fixture {
    Skeleton skel = test::make_humanoid(true);
    std::vector<test::Reach> reaches = test::make_reaches(skel, 16, 21u);
    test::PoseBuffers start = test::relaxed_pose(skel);
};

const Fixture& fixture() {
    static const Fixture f;
    return f;
}

template <bool kDls>
void BM_IkSolve(benchmark::State& state) {
    const Fixture& f = fixture();
    test::PoseBuffers pose = f.start;
    IkSettings st;
    st.max_iterations = static_cast<int>(state.range(0));
    st.tolerance = 1e-3f;
    size_t i = 0;
    int64_t iterations = 0;
    for (auto _ : state) {
        const test::Reach& r = f.reaches[i++ % f.reaches.size()];
        for (int j : r.chain) {
            const auto u = static_cast<size_t>(j);
            pose.r[u] = f.start.r[u];
            pose.m[u] = f.start.m[u];
        }
        IkTarget t;
        t.position = r.position;
        const IkResult res = kDls ? solve_dls(f.skel, r.chain, pose.view(), t, st) : solve_ccd(f.skel, r.chain, pose.view(), t, st);
        iterations += res.iterations;
        benchmark::DoNotOptimize(res);
    }
    state.counters["iters/solve"] = benchmark::Counter(static_cast<double>(iterations) / static_cast<double>(state.iterations()));
}
BENCHMARK_TEMPLATE(BM_IkSolve, false)->Name("CCD/max_iterations")->Arg(4)->Arg(10)->Arg(50);
BENCHMARK_TEMPLATE(BM_IkSolve, true)->Name("DLS/max_iterations")->Arg(4)->Arg(10)->Arg(50);

// Mean error after each iteration over all reaches (tolerance 0 so every solve runs 50 iterations).
void write_curves() {
    const Fixture& f = fixture();
    constexpr int kIters = 50;
    std::vector<double> mean[2];
    for (auto& m : mean) m.assign(kIters, 0.0);
    for (const auto& r : f.reaches) {
        for (int s = 0; s < 2; ++s) {
            test::PoseBuffers pose = f.start;
            IkTarget t;
            t.position = r.position;
            IkSettings st;
            st.max_iterations = kIters;
            st.tolerance = 0.0f;
            std::vector<float> curve(kIters, 0.0f);
            const IkResult res = s == 0 ? solve_ccd(f.skel, r.chain, pose.view(), t, st, curve)
                                        : solve_dls(f.skel, r.chain, pose.view(), t, st, curve);
            for (int k = res.iterations; k < kIters; ++k) curve[static_cast<size_t>(k)] = res.position_error;
            for (int k = 0; k < kIters; ++k) mean[s][static_cast<size_t>(k)] += curve[static_cast<size_t>(k)] / static_cast<double>(f.reaches.size());
        }
    }
    const char* env = std::getenv("ALOHA_IK_CSV");
    const char* path = env ? env : "ik_convergence.csv";
    if (std::FILE* out = std::fopen(path, "w")) {
        std::fprintf(out, "iteration,ccd_mean_error_m,dls_mean_error_m\n");
        for (int k = 0; k < kIters; ++k)
            std::fprintf(out, "%d,%.9g,%.9g\n", k + 1, mean[0][static_cast<size_t>(k)], mean[1][static_cast<size_t>(k)]);
        std::fclose(out);
        std::printf("wrote %s\n", path);
    } else {
        std::fprintf(stderr, "%s: cannot open for writing\n", path);
    }
}

}  // namespace
}  // namespace aloha

int main(int argc, char** argv) {
    aloha::write_curves();
    benchmark::Initialize(&argc, argv);
    if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
    benchmark::RunSpecifiedBenchmarks();
    benchmark::Shutdown();
    return 0;
}
