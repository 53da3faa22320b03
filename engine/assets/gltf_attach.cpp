// Places every mesh node of a glTF character on its skeleton: skinned meshes through their skin
// (a second skin's differing inverse bind matrices resolved per vertex), rigid parts bound with
// weight 1 to the nearest joint at or above their node; then one note per kind of change.
#include "engine/anim/pose.hpp"
#include "engine/assets/gltf_detail.hpp"

#include <cmath>

namespace aloha::gltf_detail {

namespace {

// World (scene) transform of `node` from the local transforms of it and its ancestors.
Result<glm::mat4> node_world(const tinygltf::Model& model, const std::vector<int>& parents, int node, const std::string& file) {
    glm::mat4 m(1.0f);
    for (int a = node; a >= 0; a = parents[static_cast<size_t>(a)]) {
        Result<glm::mat4> local = node_local_matrix(model, a, file);
        if (!local.ok()) return local.error();
        m = local.value() * m;
    }
    return m;
}

bool near_identity(const glm::mat4& m) {
    for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r)
            if (std::abs(m[c][r] - (c == r ? 1.0f : 0.0f)) > 1e-5f) return false;
    return true;
}

// Applies `a` to positions and (by its inverse transpose) to normals; reverses triangle winding when
// `flip`.
void transform_mesh(GltfSkinnedMesh& m, const glm::mat4& a, bool flip) {
    const glm::mat3 normal_matrix = glm::transpose(glm::inverse(glm::mat3(a)));
    for (glm::vec3& p : m.positions) p = glm::vec3(a * glm::vec4(p, 1.0f));
    for (glm::vec3& n : m.normals) n = glm::normalize(normal_matrix * n);
    if (flip)
        for (size_t t = 0; t + 2 < m.indices.size(); t += 3) std::swap(m.indices[t + 1], m.indices[t + 2]);
}

// A vertex of skin k is stored for skinning with the canonical inverse binds: v' = D(j) v with
// D(j) = canonical_ibm(j)^-1 * ibm_k(j), exact when every joint of the vertex has the same D.
void rebind_to_canonical(GltfSkinnedMesh& m, const std::vector<glm::mat4>& d_of_runtime, const std::vector<uint8_t>& is_identity,
                         size_t* mismatched) {
    for (size_t v = 0; v < m.positions.size(); ++v) {
        const uint16_t j0 = m.joints[v][0];  // weights are sorted: the largest first
        bool all_identity = true;
        for (int k = 0; k < 4; ++k)
            if (m.weights[v][k] > 0.0f && !is_identity[m.joints[v][k]]) all_identity = false;
        if (all_identity) continue;
        const glm::mat4& d = d_of_runtime[j0];
        const glm::vec3 p = glm::vec3(d * glm::vec4(m.positions[v], 1.0f));
        for (int k = 1; k < 4; ++k) {
            if (!(m.weights[v][k] > 0.0f)) continue;
            const glm::vec3 q = glm::vec3(d_of_runtime[m.joints[v][k]] * glm::vec4(m.positions[v], 1.0f));
            if (glm::length(q - p) > 1e-4f * (1.0f + glm::length(p))) {
                ++*mismatched;
                break;
            }
        }
        m.positions[v] = p;
        m.normals[v] = glm::normalize(glm::transpose(glm::inverse(glm::mat3(d))) * m.normals[v]);
    }
}

void add_notes(const MeshNotes& n, std::vector<std::string>* notes) {
    auto count = [](size_t k, const std::string& what) {
        return std::to_string(k) + " " + (k == 1 ? what : what == "vertex" ? std::string("vertices") : what + "s");
    };
    if (n.unnormalised_primitives)
        notes->push_back(count(n.unnormalised_vertices, "vertex") + " in " + count(n.unnormalised_primitives, "primitive") +
                         " had joint weights not summing to 1; normalised");
    if (n.eight_influence_primitives)
        notes->push_back(count(n.eight_influence_primitives, "primitive") + " with JOINTS_1/WEIGHTS_1: the 4 largest of 8 influences kept, renormalised");
    if (n.flat_normal_primitives)
        notes->push_back(count(n.flat_normal_primitives, "primitive") + " without NORMAL: flat normals computed, as glTF requires");
    if (n.morph_primitives)
        notes->push_back(count(n.morph_primitives, "primitive") + " with morph targets: the shape at the default weights is kept (" +
                         std::to_string(n.morph_applied_primitives) + " moved by non-zero defaults); morph weights are not animated");
    if (n.skipped_primitives) notes->push_back(count(n.skipped_primitives, "point or line primitive") + " left out (only triangles are drawn)");
    if (n.bind_mismatch_vertices)
        notes->push_back(count(n.bind_mismatch_vertices, "vertex") + " of a second skin whose joints disagree on the bind pose: bound at their largest weight's joint");
    if (n.untextured_primitives)
        notes->push_back(count(n.untextured_primitives, "primitive") + " using a textured material without its TEXCOORD set: drawn with the base colour only");
    if (n.coloured_primitives)
        notes->push_back(count(n.coloured_primitives, "primitive") + " with COLOR_0: vertex colours multiply the base colour");
    if (!n.unattached.empty()) {
        std::string list;
        for (const std::string& s : n.unattached) list += (list.empty() ? "" : ", ") + s;
        notes->push_back(list + ": mesh with no skin and no joint above it; left out");
    }
}

// The rest of the library takes a mesh's bind space to be the skeleton's model space at rest
// (inverse(inverse bind) = the joint's rest model matrix). Files may bind in another space: gltfpack's
// quantised meshes keep integer positions and fold the dequantisation X into every inverse bind matrix.
// X = rest_model(root) * inverse_bind(root) for skin 0's first root joint (its rest transform, which
// carries the folded nodes above it); when it is not the identity, vertices become X v and inverse binds
// inverse_bind * X^-1, which leaves every skinned position unchanged (model * inverse_bind * X^-1 * X v),
// so the triangles keep their winding even when X mirrors. Returns whether anything moved.
bool bind_space_to_model_space(GltfCharacter* out, const std::vector<int>& skin0_raw) {
    const RawSkeleton& s = out->skeleton;
    int anchor = -1;
    for (int raw : skin0_raw)
        if (s.joints[static_cast<size_t>(raw)].parent < 0) {
            anchor = raw;
            break;
        }
    if (anchor < 0) return false;
    const RawJoint& root = s.joints[static_cast<size_t>(anchor)];
    const glm::mat4 x = trs_matrix(root.translation, root.rotation, root.scale) * out->inverse_bind_matrices[static_cast<size_t>(anchor)];
    const float det = glm::determinant(glm::mat3(x));
    if (near_identity(x) || !std::isfinite(det) || !(std::abs(det) > 1e-30f)) return false;
    const glm::mat4 x_inv = glm::inverse(x);
    for (GltfSkinnedMesh& m : out->meshes) transform_mesh(m, x, false);
    for (glm::mat4& ibm : out->inverse_bind_matrices) ibm = ibm * x_inv;
    return true;
}

}  // namespace

Status attach_meshes(const tinygltf::Model& model, const std::vector<int>& parents, const SkinSet& skins, const std::vector<int>& runtime_of_raw,
                     const std::vector<MaterialUv>& material_uv, const std::string& file, GltfCharacter* out) {
    const size_t joints = runtime_of_raw.size();
    std::vector<std::vector<int>> runtime_of_skin_joint(skins.raw_of_skin_joint.size());
    for (size_t k = 0; k < runtime_of_skin_joint.size(); ++k)
        for (int raw : skins.raw_of_skin_joint[k]) runtime_of_skin_joint[k].push_back(runtime_of_raw[static_cast<size_t>(raw)]);
    MeshNotes notes;
    for (size_t i = 0; i < model.nodes.size(); ++i) {
        const tinygltf::Node& node = model.nodes[i];
        const std::string nw = "nodes[" + std::to_string(i) + "]";
        if (node.skin >= 0 && static_cast<size_t>(node.skin) >= model.skins.size())
            return make_error(file, "skin " + std::to_string(node.skin) + " is out of range (the file has " + std::to_string(model.skins.size()) + " skins)", 0, 0, nw);
        if (node.mesh < 0) continue;
        if (static_cast<size_t>(node.mesh) >= model.meshes.size())
            return make_error(file, "mesh " + std::to_string(node.mesh) + " is out of range (the file has " + std::to_string(model.meshes.size()) + " meshes)", 0, 0, nw);
        PrimitiveBinding binding;
        binding.morph_weights = !node.weights.empty() ? &node.weights : &model.meshes[static_cast<size_t>(node.mesh)].weights;
        const size_t first = out->meshes.size();
        if (node.skin >= 0) {
            const auto k = static_cast<size_t>(node.skin);
            binding.runtime_of_skin_joint = &runtime_of_skin_joint[k];
            if (Status s = read_mesh(model, static_cast<int>(i), node.mesh, binding, out->materials, material_uv, file, &notes, &out->meshes); !s.ok())
                return s;
            std::vector<glm::mat4> d(joints, glm::mat4(1.0f));
            std::vector<uint8_t> identity(joints, 1);
            bool any = false;
            for (size_t s = 0; s < skins.raw_of_skin_joint[k].size(); ++s) {
                const auto raw = static_cast<size_t>(skins.raw_of_skin_joint[k][s]);
                const glm::mat4 delta = glm::inverse(out->inverse_bind_matrices[raw]) * skins.skin_ibm[k][s];
                if (near_identity(delta)) continue;
                d[static_cast<size_t>(runtime_of_raw[raw])] = delta;
                identity[static_cast<size_t>(runtime_of_raw[raw])] = 0;
                any = true;
            }
            if (any)
                for (size_t m = first; m < out->meshes.size(); ++m) rebind_to_canonical(out->meshes[m], d, identity, &notes.bind_mismatch_vertices);
            continue;
        }
        // Rigid part: the nearest joint at or above the node, and the transforms of the nodes between.
        glm::mat4 between(1.0f);
        int a = static_cast<int>(i);
        while (a >= 0 && skins.joint_of_node[static_cast<size_t>(a)] < 0) {
            Result<glm::mat4> local = node_local_matrix(model, a, file);
            if (!local.ok()) return local.error();
            between = local.value() * between;
            a = parents[static_cast<size_t>(a)];
        }
        if (a < 0) {
            notes.unattached.push_back(nw);
            continue;
        }
        const auto raw = static_cast<size_t>(skins.joint_of_node[static_cast<size_t>(a)]);
        const glm::mat4& ibm = out->inverse_bind_matrices[raw];
        if (!(std::abs(glm::determinant(ibm)) > 1e-12f))
            return make_error(file, "inverse bind matrix of joint nodes[" + std::to_string(a) + "] is singular; the rigid mesh of " + nw + " cannot be bound to it", 0, 0, nw);
        Result<glm::mat4> world = node_world(model, parents, static_cast<int>(i), file);
        if (!world.ok()) return world.error();
        binding.rigid_joint = static_cast<uint16_t>(runtime_of_raw[raw]);
        if (Status s = read_mesh(model, static_cast<int>(i), node.mesh, binding, out->materials, material_uv, file, &notes, &out->meshes); !s.ok())
            return s;
        // glTF: a negative determinant of the node's global transform means clockwise front faces.
        const bool flip = glm::determinant(glm::mat3(world.value())) < 0.0f;
        for (size_t m = first; m < out->meshes.size(); ++m) transform_mesh(out->meshes[m], glm::inverse(ibm) * between, flip);
    }
    // A textured material on a primitive without its TEXCOORD set: a copy without the textures that need UVs
    // (a one-texel emissive texture, an emissive factor alone, does not; without its map, metallic-roughness
    // keeps its factors).
    auto needs_uvs = [&](const SurfaceMaterial& s) {
        const bool emissive_map = s.emissive_texture >= 0 && out->textures[static_cast<size_t>(s.emissive_texture)].width * out->textures[static_cast<size_t>(s.emissive_texture)].height > 1;
        return s.texture >= 0 || s.normal_texture >= 0 || s.occlusion_texture >= 0 || s.metallic_roughness_texture >= 0 || emissive_map;
    };
    std::vector<int> plain(out->materials.size(), -1);
    for (GltfSkinnedMesh& m : out->meshes) {
        if (m.material < 0 || !needs_uvs(out->materials[static_cast<size_t>(m.material)]) || !m.uvs.empty()) continue;
        int& copy = plain[static_cast<size_t>(m.material)];
        if (copy < 0) {
            SurfaceMaterial c = out->materials[static_cast<size_t>(m.material)];
            c.name += " (no TEXCOORD)";
            c.texture = c.normal_texture = c.occlusion_texture = c.metallic_roughness_texture = -1;
            if (needs_uvs(c)) c.emissive_texture = -1;
            copy = static_cast<int>(out->materials.size());
            out->materials.push_back(std::move(c));
        }
        m.material = copy;
    }
    if (!skins.raw_of_skin_joint.empty() && !out->meshes.empty() && bind_space_to_model_space(out, skins.raw_of_skin_joint[0]))
        out->notes.push_back("skins[0] binds its meshes in a space other than the skeleton's rest space (quantised or offset vertices); "
                             "vertices and inverse bind matrices were moved into the rest space, skinning unchanged");
    add_notes(notes, &out->notes);
    return {};
}

}  // namespace aloha::gltf_detail
