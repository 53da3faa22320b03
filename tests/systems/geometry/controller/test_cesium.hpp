// Test helper: CesiumMan (a shared third-party asset, never in the repository; callers find it with
// tests/common/test_assets.hpp and skip without it) as a geometry type with muscles fitted per bone.
#pragma once

#include "engine/assets/gltf_loader.hpp"
#include "systems/geometry/controller/character_geometry.hpp"
#include "systems/geometry/controller/gltf_character_mesh.hpp"
#include "systems/geometry/muscle/muscle_fit.hpp"

#include <memory>
#include <string>

namespace aloha::test {

/// CesiumMan's geometry type and first clip, or the error that stopped building them.
struct Cesium {
    std::unique_ptr<CharacterGeometry> geometry;
    RawAnimation clip;
    std::string error;
};

/// The character at `path` (muscles fitted per bone) with its first clip, built once per test binary.
inline const Cesium& load_cesium(const std::string& path) {
    static const Cesium c = [&] {
        Cesium out;
        auto loaded = load_gltf_character(path);
        if (!loaded.ok()) {
            out.error = loaded.error().to_string();
            return out;
        }
        auto skeleton = build_skeleton(loaded.value().skeleton, path);
        if (!skeleton.ok()) {
            out.error = skeleton.error().to_string();
            return out;
        }
        CharacterMesh mesh = character_mesh_from_gltf(loaded.value(), skeleton.value());
        const std::vector<glm::mat4> rest = rest_model_matrices(skeleton.value());
        const std::vector<glm::vec3> rest_positions = skin_mesh_positions(mesh, rest);
        MuscleFitOptions fit;
        fit.source_name = path;
        auto muscles = fit_muscles_per_bone(skeleton.value(), rest, rest_positions, widen_joints(mesh.joints), mesh.weights, fit);
        if (!muscles.ok()) {
            out.error = muscles.error().to_string();
            return out;
        }
        CharacterGeometryDesc desc;
        desc.type = 7;
        desc.name = path;
        desc.skeleton = std::move(skeleton).value();
        desc.muscles = std::move(muscles).value();
        desc.rest_model = rest;
        desc.mesh = std::move(mesh);
        auto geometry = CharacterGeometry::create(std::move(desc));
        if (!geometry.ok()) {
            out.error = geometry.error().to_string();
            return out;
        }
        out.geometry = std::move(geometry).value();
        out.clip = loaded.value().clips.front();
        return out;
    }();
    return c;
}

}  // namespace aloha::test
