// Test helper: a textured, skinned cylinder on a two-joint chain, as plain vertex arrays and as a glTF
// document (tests/common/gltf_builder.hpp), for the loader tests that write the same character in other
// encodings (quantised, compressed, re-packed by gltfpack) and compare what comes back.
#pragma once

#include "tests/common/gltf_builder.hpp"
#include "tests/common/png_bytes.hpp"

#include <glm/gtc/matrix_transform.hpp>

#include <cmath>
#include <cstdint>
#include <vector>

namespace aloha::test {

/// Vertex arrays of the cylinder: radius 0.2 m, 2 m tall along +y from the origin, `rings` rings of
/// `segments` vertices (the seam vertex repeated for the texture). Joint 0 "root" at the origin, joint 1
/// "tip" at (0, 1, 0); weights blend linearly from root (y = 0) to tip (y = 2).
struct SkinnedCylinder {
    std::vector<glm::vec3> positions, normals;
    std::vector<glm::vec2> uvs;
    std::vector<uint16_t> joints;  ///< 4 per vertex
    std::vector<glm::vec4> weights;
    std::vector<uint16_t> indices;

    explicit SkinnedCylinder(int rings = 6, int segments = 8) {
        for (int r = 0; r < rings; ++r)
            for (int s = 0; s <= segments; ++s) {
                const float a = 6.2831853f * static_cast<float>(s) / static_cast<float>(segments);
                const float y = 2.0f * static_cast<float>(r) / static_cast<float>(rings - 1);
                positions.emplace_back(0.2f * std::cos(a), y, 0.2f * std::sin(a));
                normals.emplace_back(std::cos(a), 0.0f, std::sin(a));
                uvs.emplace_back(static_cast<float>(s) / static_cast<float>(segments), 0.1f + 0.4f * y);
                joints.insert(joints.end(), {0, 1, 0, 0});
                weights.emplace_back(1.0f - 0.5f * y, 0.5f * y, 0.0f, 0.0f);
            }
        const int row = segments + 1;
        for (int r = 0; r + 1 < rings; ++r)
            for (int s = 0; s < segments; ++s) {
                const auto a = static_cast<uint16_t>(r * row + s), b = static_cast<uint16_t>(a + 1);
                const auto c = static_cast<uint16_t>(a + row), d = static_cast<uint16_t>(c + 1);
                indices.insert(indices.end(), {a, c, b, b, c, d});
            }
    }

    /// Rest model matrices of the two joints (the inverse bind matrices are their inverses).
    static glm::mat4 root_rest() { return glm::mat4(1.0f); }
    static glm::mat4 tip_rest() { return glm::translate(glm::mat4(1.0f), glm::vec3(0.0f, 1.0f, 0.0f)); }
};

/// A 2 x 2 RGBA8 PNG (red, green, blue, white) written with stb_image_write.
inline std::vector<unsigned char> checker_png() {
    return png_bytes({255, 0, 0, 255, 0, 255, 0, 255, 0, 0, 255, 255, 255, 255, 255, 255}, 2, 2);
}

/// The skeleton, skin, textured material and a mesh node of the cylinder in `b`, with the primitive's
/// attributes given (accessor indices, already added). Nodes: 0 tip, 1 root (child 0), 2 the mesh
/// node (skin 0, mesh 0), which gets `mesh_node` merged in (e.g. a translation and scale). The skin's
/// inverse bind matrices are the rest inverses times `bind` (gltfpack folds its dequantisation there).
inline void add_cylinder_character(GltfBuilder& b, const nlohmann::json& attributes, int indices, const nlohmann::json& mesh_node = nlohmann::json::object(),
                                   const glm::mat4& bind = glm::mat4(1.0f), const nlohmann::json& texture_info_extensions = nlohmann::json()) {
    const int tip = b.node({{"name", "tip"}, {"translation", {0, 1, 0}}});
    const int root = b.node({{"name", "root"}, {"children", {tip}}});
    const int image = b.image(checker_png());
    b.doc["textures"] = nlohmann::json::array({{{"source", image}}});
    nlohmann::json info = {{"index", 0}};
    if (!texture_info_extensions.is_null()) info["extensions"] = texture_info_extensions;
    b.doc["materials"].push_back({{"pbrMetallicRoughness", {{"baseColorTexture", info}}}});
    const int mesh = b.mesh(nlohmann::json::array({{{"attributes", attributes}, {"indices", indices}, {"material", 0}}}));
    nlohmann::json node = {{"name", "body"}, {"mesh", mesh}, {"skin", 0}};
    node.update(mesh_node);
    const int body = b.node(node);
    b.skin({root, tip}, {glm::inverse(SkinnedCylinder::root_rest()) * bind, glm::inverse(SkinnedCylinder::tip_rest()) * bind});
    b.root(root);
    b.root(body);
}

/// The plain (float) glTF of the cylinder.
inline GltfBuilder plain_cylinder(const SkinnedCylinder& c) {
    GltfBuilder b;
    const nlohmann::json attributes = {{"POSITION", b.vec3(c.positions)}, {"NORMAL", b.vec3(c.normals)}, {"TEXCOORD_0", b.vec2(c.uvs)},
                                       {"JOINTS_0", b.joints(c.joints)}, {"WEIGHTS_0", b.vec4(c.weights)}};
    add_cylinder_character(b, attributes, b.indices(c.indices));
    return b;
}

}  // namespace aloha::test
