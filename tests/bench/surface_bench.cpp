// Load-time surface work on meshes of a character's size and above: closest-point maps between two
// resolutions of one surface (geomorphs, the fidelity deviation) and the simplifier's two-sided distance bound
// (skinned levels with simplify_error). Run: build/release/tests/bench/surface_bench (time per whole call).
#include "systems/geometry/body_skin/surface_map.hpp"
#include "systems/geometry/controller/simplified_indices.hpp"

#include <benchmark/benchmark.h>
#include <glm/glm.hpp>

#include <cmath>
#include <numbers>
#include <vector>

namespace {

struct Mesh {
    std::vector<glm::vec3> positions;
    std::vector<uint32_t> indices;
};

// A closed latitude-longitude sphere of about 2 * rings * segments triangles, 1.8 units across, with radial bumps
// (a body's folds: a smooth sphere would simplify to a handful of triangles) and poles closed by fans.
Mesh bumpy_sphere(uint32_t rings, uint32_t segments) {
    const float pi = std::numbers::pi_v<float>;
    Mesh m;
    const auto at = [&](float theta, float phi) {
        const float r = 0.9f * (1.0f + 0.04f * std::sin(7.0f * theta) * std::sin(5.0f * phi));
        return r * glm::vec3(std::cos(phi) * std::cos(theta), std::cos(phi) * std::sin(theta), std::sin(phi));
    };
    m.positions.push_back({0.0f, 0.0f, -0.9f});
    for (uint32_t r = 1; r < rings; ++r)
        for (uint32_t s = 0; s < segments; ++s)
            m.positions.push_back(at(2.0f * pi * float(s) / float(segments), -0.5f * pi + pi * float(r) / float(rings)));
    m.positions.push_back({0.0f, 0.0f, 0.9f});
    const auto ring = [&](uint32_t r, uint32_t s) { return 1 + (r - 1) * segments + s % segments; };
    const uint32_t top = static_cast<uint32_t>(m.positions.size() - 1);
    for (uint32_t s = 0; s < segments; ++s) {
        m.indices.insert(m.indices.end(), {0u, ring(1, s + 1), ring(1, s)});
        for (uint32_t r = 1; r + 1 < rings; ++r)
            m.indices.insert(m.indices.end(), {ring(r, s), ring(r, s + 1), ring(r + 1, s + 1), ring(r, s), ring(r + 1, s + 1), ring(r + 1, s)});
        m.indices.insert(m.indices.end(), {ring(rings - 1, s), ring(rings - 1, s + 1), top});
    }
    return m;
}

// Arg: triangles of the source (about). A target with 1.5x the resolution is located on it.
void BM_MapSurface(benchmark::State& state) {
    const auto side = static_cast<uint32_t>(std::sqrt(double(state.range(0)) / 4.0));
    const Mesh source = bumpy_sphere(side, 2 * side);
    const Mesh target = bumpy_sphere(side * 3 / 2, 3 * side);
    for (auto _ : state) benchmark::DoNotOptimize(aloha::map_surface(source.positions, source.indices, target.positions));
    state.counters["source_triangles"] = double(source.indices.size() / 3);
    state.counters["targets"] = double(target.positions.size());
}
BENCHMARK(BM_MapSurface)->Arg(5000)->Arg(20000)->Arg(80000)->Unit(benchmark::kMillisecond);

// Arg: triangles (about). The skinned_fine level's bound: 0.6% of the extent.
void BM_SimplifyIndices(benchmark::State& state) {
    const auto side = static_cast<uint32_t>(std::sqrt(double(state.range(0)) / 4.0));
    const Mesh mesh = bumpy_sphere(side, 2 * side);
    size_t kept = 0;
    for (auto _ : state) {
        const aloha::SimplifiedIndices s = aloha::simplify_indices(mesh.positions, mesh.indices, 0.006f);
        kept = s.indices.size() / 3;
        benchmark::DoNotOptimize(s.indices.data());
    }
    state.counters["triangles"] = double(mesh.indices.size() / 3);
    state.counters["kept"] = double(kept);
}
BENCHMARK(BM_SimplifyIndices)->Arg(5000)->Arg(20000)->Arg(80000)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
