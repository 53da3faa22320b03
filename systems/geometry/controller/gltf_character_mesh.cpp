// glTF character -> CharacterMesh.
#include "systems/geometry/controller/gltf_character_mesh.hpp"

namespace aloha {

CharacterMesh character_mesh_from_gltf(const GltfCharacter& character, const Skeleton& skeleton) {
    CharacterMesh out;
    bool any_uvs = false, any_colours = false;
    for (const GltfSkinnedMesh& m : character.meshes) {
        any_uvs = any_uvs || !m.uvs.empty();
        any_colours = any_colours || !m.colours.empty();
    }
    const auto default_material = static_cast<uint16_t>(character.materials.size());
    for (const GltfSkinnedMesh& m : character.meshes) {
        const auto base = static_cast<uint32_t>(out.positions.size());
        if (any_uvs) {
            if (m.uvs.empty()) out.uvs.resize(out.uvs.size() + m.positions.size(), glm::vec2(0.0f));
            else out.uvs.insert(out.uvs.end(), m.uvs.begin(), m.uvs.end());
        }
        if (any_colours) {  // white where a primitive has none
            if (m.colours.empty()) out.colours.resize(out.colours.size() + m.positions.size(), glm::vec4(1.0f));
            else out.colours.insert(out.colours.end(), m.colours.begin(), m.colours.end());
        }
        out.vertex_material.resize(out.vertex_material.size() + m.positions.size(),
                                   m.material >= 0 ? static_cast<uint16_t>(m.material) : default_material);
        out.positions.insert(out.positions.end(), m.positions.begin(), m.positions.end());
        out.normals.insert(out.normals.end(), m.normals.begin(), m.normals.end());
        out.joints.insert(out.joints.end(), m.joints.begin(), m.joints.end());
        out.weights.insert(out.weights.end(), m.weights.begin(), m.weights.end());
        for (const uint32_t i : m.indices) out.indices.push_back(base + i);
    }
    const auto source = skeleton.source_index();
    out.inverse_bind.assign(source.size(), glm::mat4(1.0f));
    for (size_t r = 0; r < source.size(); ++r) {
        const auto raw = static_cast<size_t>(source[r]);
        if (raw < character.inverse_bind_matrices.size()) out.inverse_bind[r] = character.inverse_bind_matrices[raw];
    }
    return out;
}

std::vector<SurfaceMaterial> gltf_surface_materials(const GltfCharacter& character) {
    std::vector<SurfaceMaterial> out = character.materials;
    SurfaceMaterial fallback;
    fallback.name = "glTF default material";
    out.push_back(fallback);
    return out;
}

std::vector<glm::ivec4> widen_joints(std::span<const glm::u16vec4> joints) {
    std::vector<glm::ivec4> out(joints.size());
    for (size_t i = 0; i < joints.size(); ++i) out[i] = glm::ivec4(joints[i]);
    return out;
}

}  // namespace aloha
