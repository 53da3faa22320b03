// Muscle layer cost per character: MuscleShapeJob + MuscleTessellateJob over the humanoid layout
// (CMU skeleton, data/characters/humanoid_muscles.json) for a batch of posed characters, at several
// tessellation settings (theta_steps T, phi_steps P). Counters: ns_per_vertex and us_per_character are
// plain numbers in ns / us (Google Benchmark prints an "s" suffix after inverted rates; ignore it).
#include "systems/geometry/muscle/muscle_loader.hpp"
#include "systems/geometry/muscle/muscle_shape_job.hpp"
#include "systems/geometry/muscle/muscle_tessellate_job.hpp"
#include "tests/systems/geometry/muscle/test_skeletons.hpp"

#include <benchmark/benchmark.h>

#include <cstdio>
#include <cstdlib>

namespace {

constexpr int kCharacters = 256;

struct Fixture {
    aloha::Skeleton skeleton = aloha::test::make_cmu_skeleton();
    aloha::MuscleSet muscles;
    std::vector<glm::mat4> model;  // kCharacters posed characters
    std::vector<glm::vec3> centres, radii;
    std::vector<glm::quat> rotations;

    Fixture() {
        auto set = aloha::load_muscle_set(std::string(ALOHA_SOURCE_DIR) + "/data/characters/humanoid_muscles.json", skeleton);
        if (!set.ok()) {
            std::fprintf(stderr, "%s\n", set.error().to_string().c_str());
            std::abort();
        }
        muscles = set.value();
        const size_t nj = static_cast<size_t>(skeleton.joint_count());
        std::vector<glm::quat> rot(nj);
        for (int c = 0; c < kCharacters; ++c) {  // deterministic varied poses
            for (size_t j = 0; j < nj; ++j)
                rot[j] = glm::angleAxis(0.3f * std::sin(0.7f * c + 1.3f * j), glm::normalize(glm::vec3(1, 0.3f * j, 0.5f)));
            const auto m = aloha::test::pose_model(skeleton, rot);
            model.insert(model.end(), m.begin(), m.end());
        }
        const size_t shapes = static_cast<size_t>(kCharacters * muscles.size());
        centres.resize(shapes);
        radii.resize(shapes);
        rotations.resize(shapes);
    }
};

Fixture& fixture() {
    static Fixture f;
    return f;
}

void BM_MuscleShape(benchmark::State& state) {
    Fixture& f = fixture();
    aloha::MuscleShapeJob job{&f.muscles, f.model, f.centres, f.rotations, f.radii};
    if (!job.Validate()) state.SkipWithError("invalid shape job");
    for (auto _ : state) {
        job.Run();
        benchmark::DoNotOptimize(f.radii.data());
    }
    state.counters["ns_per_character"] =
        benchmark::Counter(kCharacters, benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
    state.counters["muscles"] = f.muscles.size();
}

// Shape + tessellation at (T, P) = (range(0), range(1)).
void BM_MuscleShapeTessellate(benchmark::State& state) {
    Fixture& f = fixture();
    const auto T = static_cast<uint32_t>(state.range(0)), P = static_cast<uint32_t>(state.range(1));
    const aloha::SuperEllipsoidTables tables(T, P, f.muscles);
    const size_t vertices = f.centres.size() * tables.vertices_per_muscle();
    std::vector<glm::vec3> pos(vertices), nrm(vertices);
    aloha::MuscleShapeJob shape{&f.muscles, f.model, f.centres, f.rotations, f.radii};
    aloha::MuscleTessellateJob tess{&tables, f.centres, f.rotations, f.radii, pos, nrm};
    if (!shape.Validate() || !tess.Validate()) state.SkipWithError("invalid job");
    for (auto _ : state) {
        shape.Run();
        tess.Run();
        benchmark::DoNotOptimize(pos.data());
        benchmark::DoNotOptimize(nrm.data());
    }
    using C = benchmark::Counter;
    state.counters["ns_per_vertex"] = C(static_cast<double>(vertices) * 1e-9, C::kIsIterationInvariantRate | C::kInvert);
    state.counters["us_per_character"] = C(kCharacters * 1e-6, C::kIsIterationInvariantRate | C::kInvert);
    state.counters["vertices_per_character"] = static_cast<double>(vertices / kCharacters);
}

}  // namespace

BENCHMARK(BM_MuscleShape)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_MuscleShapeTessellate)->Args({4, 3})->Args({8, 6})->Args({16, 12})->Args({32, 24})->Unit(benchmark::kMicrosecond);
BENCHMARK_MAIN();
