// Test helpers for the geometric controller: the built-in humanoid (data/characters/humanoid.json
// skeleton + humanoid_muscles.json), poses from its generated walk, a level table covering every
// method, and small comparison helpers.
#pragma once

#include "components/lod.hpp"
#include "engine/assets/humanoid_definition.hpp"
#include "systems/motion/library/gait_clip.hpp"
#include "systems/geometry/controller/character_geometry.hpp"
#include "systems/geometry/controller/geometry_controller.hpp"
#include "systems/geometry/muscle/muscle_loader.hpp"

#include <glm/glm.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <string>
#include <vector>

namespace aloha::test {

/// The humanoid type and a long walk for it: 1.4 m/s gait cycles repeated to at least 600 keys
/// (loaded once per test binary).
struct Humanoid {
    std::unique_ptr<CharacterGeometry> geometry;
    RawAnimation clip;
};

/// Loads the humanoid; fails the calling test (returns nullptr geometry) on a load error.
inline const Humanoid& humanoid() {
    static const Humanoid h = [] {
        Humanoid out;
        const std::string def_path = std::string(ALOHA_SOURCE_DIR) + "/data/characters/humanoid.json";
        const std::string muscle_path = std::string(ALOHA_SOURCE_DIR) + "/data/characters/humanoid_muscles.json";
        auto def = load_humanoid_definition(def_path);
        if (!def.ok()) return out;
        auto skeleton = build_skeleton(humanoid_skeleton(def.value(), HumanoidBody{}), def_path);
        if (!skeleton.ok()) return out;
        auto muscles = load_muscle_set(muscle_path, skeleton.value());
        if (!muscles.ok()) return out;
        auto rig = resolve_walk_rig(skeleton.value(), def_path);
        if (!rig.ok()) return out;
        stand_rig_on_rest_ground(rig.value(), skeleton.value());
        const RawAnimation cycle =
            make_gait_clip(skeleton.value(), rig.value(), find_humanoid_joints(skeleton.value()), 1.4f, "walk").clip;
        out.clip = cycle;
        while (out.clip.tracks[0].rotations.values.size() < 600)
            for (size_t j = 0; j < cycle.tracks.size(); ++j) {
                auto& dst = out.clip.tracks[j];
                const auto& src = cycle.tracks[j];
                for (size_t k = 1; k < src.rotations.values.size(); ++k) dst.rotations.values.push_back(src.rotations.values[k]);
                for (size_t k = 1; k < src.translations.values.size(); ++k)
                    dst.translations.values.push_back(src.translations.values[k]);
            }
        CharacterGeometryDesc desc;
        desc.type = 3;
        desc.name = "humanoid";
        desc.skeleton = std::move(skeleton).value();
        desc.muscles = std::move(muscles).value();
        auto geometry = CharacterGeometry::create(std::move(desc));
        if (!geometry.ok()) return out;
        out.geometry = std::move(geometry).value();
        return out;
    }();
    return h;
}

/// Model matrices of `skeleton` at key `key` of `clip` (clamped per track; rest values where a
/// track is empty). The root's horizontal travel is removed so the character stays near the origin.
inline std::vector<glm::mat4> clip_pose(const Skeleton& skeleton, const RawAnimation& clip, size_t key) {
    const size_t J = static_cast<size_t>(skeleton.joint_count());
    std::vector<glm::mat4> model(J);
    for (size_t j = 0; j < J; ++j) {
        glm::vec3 t = skeleton.rest_translations()[j];
        glm::quat r = skeleton.rest_rotations()[j];
        if (j < clip.tracks.size()) {
            const auto& tr = clip.tracks[j];
            if (!tr.translations.values.empty()) t = tr.translations.values[std::min(key, tr.translations.values.size() - 1)];
            if (!tr.rotations.values.empty()) r = tr.rotations.values[std::min(key, tr.rotations.values.size() - 1)];
        }
        const int parent = skeleton.parents()[j];
        if (parent < 0) t.x = t.z = 0.0f;
        const glm::mat4 local = glm::translate(glm::mat4(1.0f), t) * glm::mat4_cast(r) *
                                glm::scale(glm::mat4(1.0f), skeleton.rest_scales()[j]);
        model[j] = parent < 0 ? local : model[static_cast<size_t>(parent)] * local;
    }
    return model;
}

/// A grid level with method `m` at (T, P).
inline GeomLod grid_level(GeomMethod m, uint16_t T, uint16_t P, uint8_t subdiv = 0) {
    GeomLod g;
    g.method = m;
    g.theta_steps = T;
    g.phi_steps = P;
    g.subdiv_level = subdiv;
    g.layers = m == GeomMethod::Layered || m == GeomMethod::Subdivided ? (kLayerSkeleton | kLayerMuscle | kLayerFat | kLayerSkin)
                                                                      : kLayerSkeleton | kLayerSkin;
    return g;
}

/// Level table used by the tests: 0 Subdivided(8,6,1), 1 Layered(16,12), 2 Layered(8,6),
/// 3 SkinnedMesh(8,6), 4 RigidProxy, 5 Hidden.
inline std::vector<GeomLod> test_levels() {
    std::vector<GeomLod> levels = {grid_level(GeomMethod::Subdivided, 8, 6, 1), grid_level(GeomMethod::Layered, 16, 12),
                                   grid_level(GeomMethod::Layered, 8, 6),       grid_level(GeomMethod::SkinnedMesh, 8, 6),
                                   grid_level(GeomMethod::RigidProxy, 8, 6),    grid_level(GeomMethod::Hidden, 8, 6)};
    for (size_t i = 0; i < levels.size(); ++i) levels[i].level = static_cast<uint8_t>(i);
    return levels;
}

/// True when every component is finite.
inline bool finite(glm::vec3 v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

/// Largest |a[i] - b[i]|. Requires equal sizes.
inline float max_distance(std::span<const glm::vec3> a, std::span<const glm::vec3> b) {
    float d = 0.0f;
    for (size_t i = 0; i < a.size(); ++i) d = std::max(d, glm::length(a[i] - b[i]));
    return d;
}

}  // namespace aloha::test
