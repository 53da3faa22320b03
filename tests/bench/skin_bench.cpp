// Fat springs + skin per character at several (T, P); OpenSubdiv level-1 evaluation; LBS.
// Run: build-skin/tests/bench/skin_bench (items/s = characters or vertices per second).
#include "systems/geometry/spring_skin/fat_spring.hpp"
#include "systems/geometry/spring_skin/peeled.hpp"
#include "systems/geometry/spring_skin/skin_mesh.hpp"
#include "systems/geometry/spring_skin/subdivision.hpp"
#include "systems/geometry/surface_grid.hpp"

#include <benchmark/benchmark.h>
#include <glm/glm.hpp>

#include <cmath>
#include <numbers>
#include <vector>

namespace {

constexpr uint32_t kMuscles = 16;     // muscles per character (a lower-body/arm layout)
constexpr uint32_t kCharacters = 64;  // characters per batch (one LOD bucket)

// Concatenated sphere grids for `grids` muscles, jittered by `phase` so springs do work.
void make_grids(uint32_t T, uint32_t P, uint32_t grids, float phase, std::vector<glm::vec3>& pos, std::vector<glm::vec3>& nrm) {
    const float pi = std::numbers::pi_v<float>;
    pos.clear();
    nrm.clear();
    for (uint32_t g = 0; g < grids; ++g) {
        const glm::vec3 centre(0.3f * static_cast<float>(g % 8), 0.2f * static_cast<float>(g / 8) + 0.01f * std::sin(phase + static_cast<float>(g)), 0.0f);
        auto add = [&](float theta, float phi) {
            const glm::vec3 n(std::cos(phi) * std::cos(theta), std::cos(phi) * std::sin(theta), std::sin(phi));
            pos.push_back(centre + 0.05f * n);
            nrm.push_back(n);
        };
        add(0.0f, -0.5f * pi);
        for (uint32_t r = 1; r < P; ++r)
            for (uint32_t t = 0; t < T; ++t)
                add(-pi + static_cast<float>(t) * 2.0f * pi / static_cast<float>(T), -0.5f * pi + static_cast<float>(r) * pi / static_cast<float>(P));
        add(0.0f, 0.5f * pi);
    }
}

void BM_FatSpringsAndSkin(benchmark::State& state) {
    const auto T = static_cast<uint32_t>(state.range(0)), P = static_cast<uint32_t>(state.range(1));
    const uint32_t grids = kMuscles * kCharacters;
    std::vector<glm::vec3> pos_a, nrm_a, pos_b, nrm_b;
    make_grids(T, P, grids, 0.0f, pos_a, nrm_a);
    make_grids(T, P, grids, 1.0f, pos_b, nrm_b);
    const std::vector<float> thickness(grids, 0.01f);
    aloha::FatSpringPool pool(kCharacters, kMuscles, T, P);
    std::vector<glm::vec3> normals(pos_a.size());
    aloha::FatSpringJob springs;
    springs.theta_steps = T;
    springs.phi_steps = P;
    springs.thickness = thickness;
    springs.state = pool.view(0, kCharacters);
    aloha::SkinJob skin{T, P, springs.state.end, {}, normals};
    bool flip = false;
    for (auto _ : state) {
        springs.muscle_positions = flip ? pos_b : pos_a;
        springs.muscle_normals = flip ? nrm_b : nrm_a;
        skin.fallback_normals = springs.muscle_normals;
        flip = !flip;
        springs.Run();
        skin.Run();
        benchmark::DoNotOptimize(normals.data());
        benchmark::ClobberMemory();
    }
    state.SetItemsProcessed(static_cast<int64_t>(state.iterations()) * kCharacters);
    state.counters["verts_per_char"] = static_cast<double>(kMuscles * aloha::grid_vertex_count(T, P));
}
BENCHMARK(BM_FatSpringsAndSkin)->Args({4, 3})->Args({6, 4})->Args({8, 6})->Args({12, 8})->Args({16, 10})->Args({24, 14});

void BM_SubdivideLevel1(benchmark::State& state) {
    const auto T = static_cast<uint32_t>(state.range(0)), P = static_cast<uint32_t>(state.range(1));
    std::vector<glm::vec3> pos, nrm;
    make_grids(T, P, kMuscles, 0.0f, pos, nrm);
    aloha::SubdivisionCache cache;
    const aloha::SubdivisionTopology& topo = cache.get({T, P, kMuscles, 1});
    std::vector<glm::vec3> refined(topo.refined_vertex_count), normals(topo.refined_vertex_count);
    aloha::SubdivideJob job{&topo, pos, refined, normals};
    for (auto _ : state) {
        job.Run();
        benchmark::DoNotOptimize(normals.data());
        benchmark::ClobberMemory();
    }
    state.SetItemsProcessed(static_cast<int64_t>(state.iterations()));  // characters
    state.counters["refined_verts"] = static_cast<double>(topo.refined_vertex_count);
}
BENCHMARK(BM_SubdivideLevel1)->Args({8, 6})->Args({16, 10});

void BM_LinearBlendSkin(benchmark::State& state) {
    const size_t n = static_cast<size_t>(state.range(0));
    std::vector<glm::mat4> palette(32, glm::mat4(1.0f));
    for (size_t j = 0; j < palette.size(); ++j) palette[j][3] = glm::vec4(0.01f * static_cast<float>(j), 0, 0, 1);
    std::vector<glm::vec3> p(n, glm::vec3(0.1f)), nn(n, glm::vec3(0, 0, 1)), op(n), on(n);
    std::vector<glm::u16vec4> joints(n);
    std::vector<glm::vec4> weights(n, glm::vec4(0.4f, 0.3f, 0.2f, 0.1f));
    for (size_t i = 0; i < n; ++i) joints[i] = glm::u16vec4(i % 32, (i + 1) % 32, (i + 5) % 32, (i + 9) % 32);
    aloha::LinearBlendSkinJob job{palette, p, nn, joints, weights, op, on};
    for (auto _ : state) {
        job.Run();
        benchmark::DoNotOptimize(op.data());
        benchmark::ClobberMemory();
    }
    state.SetItemsProcessed(static_cast<int64_t>(state.iterations() * n));  // vertices
}
BENCHMARK(BM_LinearBlendSkin)->Arg(3273);  // vertices of a small glTF character

}  // namespace

BENCHMARK_MAIN();
