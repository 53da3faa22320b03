// GeometryController::update per character for every method on the project's humanoid
// (data/characters/humanoid.json, 31 joints, humanoid_muscles.json), with 1 and 64 characters per
// call. Poses alternate between two sets of joint rotations so the fat springs do work.
// Run: build-geomctl/tests/bench/geomctl_bench (items/s = characters/s).
#include "engine/assets/humanoid_definition.hpp"
#include "systems/geometry/controller/geometry_controller.hpp"
#include "systems/geometry/muscle/muscle_loader.hpp"

#include <benchmark/benchmark.h>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>

#include <cmath>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

namespace {

using namespace aloha;

struct Setup {
    std::unique_ptr<CharacterGeometry> geometry;
    std::vector<glm::mat4> poses[2];  // two poses per character, 64 characters each
};

// Model matrices of `s` with every non-root joint turned from its rest rotation by up to 0.3 rad
// about an axis and angle that vary with the joint and with `phase` (deterministic, walk-sized).
std::vector<glm::mat4> phase_pose(const Skeleton& s, float phase) {
    std::vector<glm::mat4> model(static_cast<size_t>(s.joint_count()));
    for (size_t j = 0; j < model.size(); ++j) {
        const glm::vec3 t = s.rest_translations()[j];
        glm::quat r = s.rest_rotations()[j];
        if (s.parents()[j] >= 0) {
            const float a = static_cast<float>(j) * 0.7f + phase;
            const glm::vec3 axis = glm::normalize(glm::vec3(1.0f, 0.5f * std::sin(a), 0.5f * std::cos(a)));
            r = r * glm::angleAxis(0.3f * std::sin(a), axis);
        }
        const glm::mat4 local = glm::translate(glm::mat4(1.0f), t) * glm::mat4_cast(r);
        model[j] = s.parents()[j] < 0 ? local : model[static_cast<size_t>(s.parents()[j])] * local;
    }
    return model;
}

const Setup& setup() {
    static const Setup st = [] {
        Setup out;
        const std::string dir = std::string(ALOHA_SOURCE_DIR) + "/data/characters/";
        auto def = load_humanoid_definition(dir + "humanoid.json");
        if (!def.ok()) return out;
        auto skeleton = build_skeleton(humanoid_skeleton(def.value(), HumanoidBody{}), "humanoid.json");
        if (!skeleton.ok()) return out;
        auto muscles = load_muscle_set(dir + "humanoid_muscles.json", skeleton.value());
        if (!muscles.ok()) return out;
        for (int f = 0; f < 2; ++f)
            for (size_t c = 0; c < 64; ++c) {
                const float phase = 0.37f * static_cast<float>(c) + 0.25f * static_cast<float>(f);
                const auto p = phase_pose(skeleton.value(), phase);
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
        case 5:  // the rule files' layered_high: with the fat layer (the blended springs step)
            g.method = GeomMethod::Layered;
            g.theta_steps = 16;
            g.phi_steps = 12;
            g.layers = kLayerSkeleton | kLayerMuscle | kLayerFat | kLayerSkin;
            break;
        case 6:  // the rule files' layered_low: (8, 6) with the fat layer
            g.method = GeomMethod::Layered;
            g.theta_steps = 8;
            g.phi_steps = 6;
            g.layers = kLayerSkeleton | kLayerMuscle | kLayerFat | kLayerSkin;
            break;
        default: g.method = GeomMethod::Subdivided; g.theta_steps = 8; g.phi_steps = 6; g.subdiv_level = 1; break;
    }
    return g;
}

// Arg 0: 0 RigidProxy, 1 SkinnedMesh(8,6), 2 Layered(8,6), 3 Layered(16,12), 4 Subdivided(8,6,1),
// 5 Layered(16,12) and 6 Layered(8,6) with all four layers (fat springs stepped; 0-4 have the skeleton layer only);
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
BENCHMARK(BM_ControllerUpdate)->ArgsProduct({{0, 1, 2, 3, 4, 5, 6}, {1, 64}})->Unit(benchmark::kMicrosecond);

}  // namespace

BENCHMARK_MAIN();
