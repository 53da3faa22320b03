// Render benchmarks: CPU upload cost per MB of deformable-mesh data, and whole frames of N instanced
// proxy boxes at 1280x720 (GPU time from timestamp queries reported as counters).
#include "engine/gpu/context.hpp"
#include "systems/render/crowd_renderer.hpp"
#include "systems/render/debug_colours.hpp"

#include <benchmark/benchmark.h>
#include <glm/gtc/matrix_transform.hpp>

#include <cmath>
#include <cstdio>
#include <cstdlib>

namespace aloha {
namespace {

gpu::Context* context() {
    static std::unique_ptr<gpu::Context> ctx = [] {
        gpu::ContextOptions o;  // device from ALOHA_DEVICE, else auto
        Result<std::unique_ptr<gpu::Context>> c = gpu::Context::create(o);
        if (!c) {
            std::fprintf(stderr, "render_bench: %s\n", c.error().to_string().c_str());
            std::exit(1);
        }
        return std::move(c).value();
    }();
    return ctx.get();
}

RenderCamera crowd_camera(float aspect) {
    RenderCamera cam;
    cam.view = glm::lookAt(glm::vec3(0, 25, 45), glm::vec3(0, 0, 0), glm::vec3(0, 1, 0));
    cam.proj = glm::perspective(glm::radians(60.0f), aspect, 0.1f, 200.0f);
    return cam;
}

// Upload cost: `chars` characters of `verts` vertices each (one topology), frames rendered into a small
// target so the measured time is the CPU copy into mapped buffers (manual time = last_upload_ms()).
void BM_UploadDeformable(benchmark::State& state) {
    gpu::Context& ctx = *context();
    const uint32_t chars = static_cast<uint32_t>(state.range(0));
    const uint32_t verts = 3000;
    auto r = CrowdRenderer::create(ctx);
    std::vector<uint32_t> idx;
    for (uint32_t i = 0; i + 2 < verts; i += 3) idx.insert(idx.end(), {i, i + 1, i + 2});
    const uint32_t topo = r.value()->register_topology(idx, verts).value();
    std::vector<glm::vec3> pos(verts), nrm(verts, glm::vec3(0, 0, 1));
    for (uint32_t i = 0; i < verts; ++i) pos[i] = glm::vec3(0.001f * i, 0.0f, 0.0f);  // degenerate: no pixels
    std::vector<DeformableMesh> meshes(chars);
    for (uint32_t c = 0; c < chars; ++c) meshes[c] = {topo, pos, nrm, glm::mat4(1.0f), colour_for_level(c % 4)};
    auto target = gpu::OffscreenTarget::create(ctx, 64, 64);
    FrameInput frame;
    frame.camera = crowd_camera(1.0f);
    frame.meshes = meshes;
    double bytes = 0;
    for (auto _ : state) {
        if (!r.value()->render(frame, target.value()).ok()) state.SkipWithError("render failed");
        state.SetIterationTime(r.value()->last_upload_ms() * 1e-3);
        bytes += double(r.value()->last_upload_bytes());
    }
    (void)r.value()->finish();
    state.SetBytesProcessed(static_cast<int64_t>(bytes));
    state.counters["MB_per_frame"] = bytes / 1e6 / double(state.iterations());
    state.counters["growth_events"] = r.value()->growth_events();
}
BENCHMARK(BM_UploadDeformable)->Arg(100)->Arg(400)->UseManualTime()->Unit(benchmark::kMillisecond)->Iterations(40);

// Whole frames of N proxy boxes (20 per character on a grid) at 1280x720 (second argument 1) or 64x36
// (second argument 0: vertex-bound, almost no fragments): wall time per frame including GPU, plus gpu_ms
// (timestamps) and upload_ms counters.
void BM_RenderProxies(benchmark::State& state) {
    gpu::Context& ctx = *context();
    const uint32_t n = static_cast<uint32_t>(state.range(0));
    auto r = CrowdRenderer::create(ctx);
    const bool hd = state.range(1) != 0;
    auto target = gpu::OffscreenTarget::create(ctx, hd ? 1280 : 64, hd ? 720 : 36);
    std::vector<ProxyInstance> proxies(n);
    const uint32_t chars = (n + 19) / 20;
    const uint32_t side = static_cast<uint32_t>(std::ceil(std::sqrt(double(chars))));
    for (uint32_t i = 0; i < n; ++i) {
        const uint32_t c = i / 20, b = i % 20;
        const glm::vec3 base(-30.0f + 60.0f * float(c % side) / float(side), 0.0f,
                             -30.0f + 60.0f * float(c / side) / float(side));
        const glm::mat4 m = glm::scale(glm::translate(glm::mat4(1.0f), base + glm::vec3(0, 0.09f * float(b), 0)),
                                       glm::vec3(0.25f, 0.09f, 0.15f));
        proxies[i] = {m, colour_for_level(int(c % 4))};
    }
    FrameInput frame;
    frame.camera = crowd_camera(1280.0f / 720.0f);
    frame.proxies = proxies;
    double gpu_ms = 0, upload_ms = 0;
    for (auto _ : state) {
        if (!r.value()->render(frame, target.value()).ok()) state.SkipWithError("render failed");
        upload_ms += r.value()->last_upload_ms();
        if (!r.value()->finish().ok()) state.SkipWithError("finish failed");
        gpu_ms += r.value()->last_gpu_ms();
    }
    state.counters["gpu_ms"] = gpu_ms / double(state.iterations());
    state.counters["upload_ms"] = upload_ms / double(state.iterations());
    state.counters["Mtri_per_s"] = double(n) * 12.0 / (gpu_ms / double(state.iterations()) * 1e3);
}
BENCHMARK(BM_RenderProxies)
    ->Args({1000, 1})
    ->Args({10000, 1})
    ->Args({20000, 1})
    ->Args({20000, 0})
   ->Unit(benchmark::kMillisecond)->Iterations(20);

// Whole frames of N deformable characters sharing one topology (a 40 x 40 vertex grid bent into a
// half-cylinder, 3,042 triangles, about a character's skin at a middle LOD) at 1280x720 (second argument 1)
// or 64x36 (0: vertex-bound): one draw in all.
void BM_RenderDeformable(benchmark::State& state) {
    gpu::Context& ctx = *context();
    const uint32_t n = static_cast<uint32_t>(state.range(0));
    constexpr uint32_t kGrid = 40;
    auto r = CrowdRenderer::create(ctx);
    const bool hd = state.range(1) != 0;
    auto target = gpu::OffscreenTarget::create(ctx, hd ? 1280 : 64, hd ? 720 : 36);
    std::vector<uint32_t> idx;
    for (uint32_t y = 0; y + 1 < kGrid; ++y)
        for (uint32_t x = 0; x + 1 < kGrid; ++x) {
            const uint32_t a = y * kGrid + x;
            idx.insert(idx.end(), {a, a + 1, a + kGrid + 1, a, a + kGrid + 1, a + kGrid});
        }
    const uint32_t topo = r.value()->register_topology(idx).value();
    std::vector<glm::vec3> pos(kGrid * kGrid), nrm(kGrid * kGrid);
    for (uint32_t y = 0; y < kGrid; ++y)
        for (uint32_t x = 0; x < kGrid; ++x) {
            const float a = 3.14159265f * float(x) / float(kGrid - 1);
            nrm[y * kGrid + x] = glm::vec3(std::cos(a), 0.0f, std::sin(a));
            pos[y * kGrid + x] = glm::vec3(0.25f * std::cos(a), 1.8f * float(y) / float(kGrid - 1), 0.25f * std::sin(a));
        }
    std::vector<DeformableMesh> meshes(n);
    const uint32_t side = static_cast<uint32_t>(std::ceil(std::sqrt(double(n))));
    for (uint32_t c = 0; c < n; ++c) {
        const glm::vec3 base(-30.0f + 60.0f * float(c % side) / float(side), 0.0f,
                             -30.0f + 60.0f * float(c / side) / float(side));
        meshes[c] = {topo, pos, nrm, glm::translate(glm::mat4(1.0f), base), colour_for_level(int(c % 4))};
    }
    FrameInput frame;
    frame.camera = crowd_camera(1280.0f / 720.0f);
    frame.meshes = meshes;
    double gpu_ms = 0, upload_ms = 0;
    for (auto _ : state) {
        if (!r.value()->render(frame, target.value()).ok()) state.SkipWithError("render failed");
        upload_ms += r.value()->last_upload_ms();
        if (!r.value()->finish().ok()) state.SkipWithError("finish failed");
        gpu_ms += r.value()->last_gpu_ms();
    }
    const double tris = double(n) * double(idx.size() / 3);
    state.counters["gpu_ms"] = gpu_ms / double(state.iterations());
    state.counters["upload_ms"] = upload_ms / double(state.iterations());
    state.counters["Mtri_per_s"] = tris / (gpu_ms / double(state.iterations()) * 1e3);
}
BENCHMARK(BM_RenderDeformable)->Args({100, 1})->Args({400, 1})->Args({400, 0})->Unit(benchmark::kMillisecond)->Iterations(10);

}  // namespace
}  // namespace aloha

BENCHMARK_MAIN();
