// GeometryController::update per character for every method on the built-in humanoid (31 joints,
// 53 muscles), with 1 and 64 characters per call. Poses alternate between two clip frames so the
// fat springs do work. Run: build-geomctl/tests/bench/geomctl_bench (items/s = characters/s).
#include "engine/assets/bvh_loader.hpp"
#include "systems/geometry/controller/geometry_controller.hpp"
#include "systems/geometry/muscle/muscle_loader.hpp"

#include <benchmark/benchmark.h>
#include <glm/gtc/matrix_transform.hpp>

#include <cstdio>
#include <memory>
#include <string>
#include <vector>

namespace {

using namespace aloha;

struct Setup {
    std::unique_ptr<CharacterGeometry> geometry;
    std::vector<glm::mat4> poses[2];  // two frames of the clip, 64 characters each
};

std::vector<glm::mat4> frame_pose(const Skeleton& s, const RawAnimation& clip, size_t key) {
    std::vector<glm::mat4> model(static_cast<size_t>(s.joint_count()));
    for (size_t j = 0; j < model.size(); ++j) {
        glm::vec3 t = s.rest_translations()[j];
        glm::quat r = s.rest_rotations()[j];
        const auto& tr = clip.tracks[j];
        if (!tr.translations.values.empty()) t = tr.translations.values[std::min(key, tr.translations.values.size() - 1)];
        if (!tr.rotations.values.empty()) r = tr.rotations.values[std::min(key, tr.rotations.values.size() - 1)];
        const glm::mat4 local = glm::translate(glm::mat4(1.0f), t) * glm::mat4_cast(r);
        model[j] = s.parents()[j] < 0 ? local : model[static_cast<size_t>(s.parents()[j])] * local;
    }
    return model;
}

const Setup& setup() {
    static const Setup st = [] {
        Setup out;
        const std::string dir = std::string(ALOHA_SOURCE_DIR) + "/data/characters/";
        auto bvh = load_bvh(dir + "131_01.bvh");
        if (!bvh.ok()) return out;
        auto skeleton = build_skeleton(bvh.value().skeleton, "131_01.bvh");
        if (!skeleton.ok()) return out;
        auto muscles = load_muscle_set(dir + "humanoid_muscles.json", skeleton.value());
        if (!muscles.ok()) return out;
        for (int f = 0; f < 2; ++f)
            for (size_t c = 0; c < 64; ++c) {
                const auto p = frame_pose(skeleton.value(), bvh.value().animation, 100 + 7 * c + 4 * static_cast<size_t>(f));
                out.poses[f].insert(out.poses[f].end(), p.begin(), p.end());
            }
        CharacterGeometryDesc desc;
        desc.name = "humanoid";
        desc.skeleton = std::move(skeleton).value();
        desc.muscles = std::move(muscles).value();
        auto g = CharacterGeometry::create(std::move(desc));
        if (g.ok()) out.geometry = std::move(g).value();
        return out;
    }();
    return st;
}

GeomLod level_of(int which) {
    GeomLod g;
    switch (which) {
        case 0: g.method = GeomMethod::RigidProxy; break;
        case 1: g.method = GeomMethod::SkinnedMesh; g.theta_steps = 8; g.phi_steps = 6; break;
        case 2: g.method = GeomMethod::Layered; g.theta_steps = 8; g.phi_steps = 6; break;
        case 3: g.method = GeomMethod::Layered; g.theta_steps = 16; g.phi_steps = 12; break;
        default: g.method = GeomMethod::Subdivided; g.theta_steps = 8; g.phi_steps = 6; g.subdiv_level = 1; break;
    }
    return g;
}

// Arg 0: 0 RigidProxy, 1 SkinnedMesh(8,6), 2 Layered(8,6), 3 Layered(16,12), 4 Subdivided(8,6,1);
// arg 1: characters per update call.
void BM_ControllerUpdate(benchmark::State& state) {
    const Setup& st = setup();
    if (!st.geometry) {
        state.SkipWithError("humanoid failed to load");
        return;
    }
    const GeomLod lod = level_of(static_cast<int>(state.range(0)));
    const auto n = static_cast<uint32_t>(state.range(1));
    GeometryController ctl(*st.geometry, std::span(&lod, 1), n);
    std::vector<uint32_t> ids(n);
    for (uint32_t c = 0; c < n; ++c) {
        ids[c] = c;
        ctl.begin_level(c, 0, -1, 0);
    }
    const size_t J = st.geometry->joint_count();
    int flip = 0;
    for (auto _ : state) {
        ctl.update(0, ids, PoseSource{st.poses[flip].data(), J}, 1.0f / 30.0f);
        flip ^= 1;
        benchmark::ClobberMemory();
    }
    state.SetItemsProcessed(static_cast<int64_t>(state.iterations()) * n);
    state.counters["verts"] = ctl.vertices_per_character(0);
    state.counters["bytes_per_char"] = static_cast<double>(ctl.bytes_per_character(0));
}
BENCHMARK(BM_ControllerUpdate)->ArgsProduct({{0, 1, 2, 3, 4}, {1, 64}})->Unit(benchmark::kMicrosecond);

}  // namespace

BENCHMARK_MAIN();
