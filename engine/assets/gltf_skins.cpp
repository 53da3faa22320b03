// glTF skins -> the character's joints: the union of every skin's joints, their rest transforms
// (non-joint ancestors folded in), unique names, and the inverse bind matrices of every skin.
#include "engine/assets/gltf_detail.hpp"

#include <cmath>
#include <set>

namespace aloha::gltf_detail {

namespace {

// The inverse bind matrices of skin `k` (identity when it has none), one per skin joint.
Result<std::vector<glm::mat4>> read_inverse_binds(const tinygltf::Model& model, size_t k, const std::string& file) {
    const tinygltf::Skin& skin = model.skins[k];
    const size_t n = skin.joints.size();
    std::vector<glm::mat4> out(n, glm::mat4(1.0f));
    if (skin.inverseBindMatrices < 0) return out;
    const std::string where = "skins[" + std::to_string(k) + "]";
    Result<std::vector<float>> ibm = read_floats(model, skin.inverseBindMatrices, TINYGLTF_TYPE_MAT4, {TINYGLTF_COMPONENT_TYPE_FLOAT},
                                                 file, where + ".inverseBindMatrices");
    if (!ibm.ok()) return ibm.error();
    const std::string at = "accessors[" + std::to_string(skin.inverseBindMatrices) + "]";
    if (ibm.value().size() < n * 16)
        return make_error(file, "has " + std::to_string(ibm.value().size() / 16) + " matrices for " + std::to_string(n) + " joints", 0, 0, at);
    for (size_t i = 0; i < n; ++i)
        for (int c = 0; c < 4; ++c)
            for (int r = 0; r < 4; ++r) {
                const float v = ibm.value()[i * 16 + static_cast<size_t>(c * 4 + r)];
                if (!std::isfinite(v)) return make_error(file, "inverse bind matrix " + std::to_string(i) + " has a NaN or infinite value", 0, 0, at);
                out[i][c][r] = v;
            }
    // The rest of the library inverts them (a joint's bind pose): a singular one has no bind pose.
    for (size_t i = 0; i < n; ++i) {
        const float det = glm::determinant(glm::mat3(out[i]));
        if (!(std::abs(det) > 1e-24f))
            return make_error(file, "inverse bind matrix " + std::to_string(i) + " is singular (determinant " + std::to_string(det) + ")", 0, 0, at);
    }
    return out;
}

}  // namespace

Result<SkinSet> read_skins(const tinygltf::Model& model, const std::vector<int>& parents, const std::string& file, GltfCharacter* out) {
    if (model.skins.empty()) return make_error(file, "file has no skins (a character needs at least one)", 0, 0, "skins");
    SkinSet set;
    set.joint_of_node.assign(model.nodes.size(), -1);
    std::vector<int> skin_nodes;  // raw joint -> node
    for (size_t k = 0; k < model.skins.size(); ++k) {
        const tinygltf::Skin& skin = model.skins[k];
        const std::string sw = "skins[" + std::to_string(k) + "]";
        if (skin.joints.empty()) return make_error(file, "skin has no joints", 0, 0, sw);
        std::set<int> seen;
        std::vector<int> raw(skin.joints.size(), -1);
        for (size_t i = 0; i < skin.joints.size(); ++i) {
            const int node = skin.joints[i];
            const std::string where = sw + ".joints[" + std::to_string(i) + "]";
            if (node < 0 || static_cast<size_t>(node) >= model.nodes.size())
                return make_error(file, "node " + std::to_string(node) + " is out of range (the file has " + std::to_string(model.nodes.size()) + " nodes)", 0, 0, where);
            if (!seen.insert(node).second) return make_error(file, "nodes[" + std::to_string(node) + "] is listed twice in the skin", 0, 0, where);
            int& j = set.joint_of_node[static_cast<size_t>(node)];
            if (j < 0) {
                j = static_cast<int>(skin_nodes.size());
                skin_nodes.push_back(node);
            }
            raw[i] = j;
        }
        set.raw_of_skin_joint.push_back(std::move(raw));
        Result<std::vector<glm::mat4>> ibm = read_inverse_binds(model, k, file);
        if (!ibm.ok()) return ibm.error();
        set.skin_ibm.push_back(std::move(ibm).value());
    }
    const size_t n = skin_nodes.size();
    if (n > 32767) return make_error(file, "skins have " + std::to_string(n) + " joints; at most 32767 are supported", 0, 0, "skins");

    // Skin 0's inverse binds are kept. A later skin k may bind its mesh in another space (its inverse
    // binds of shared joints differ by one offset B_k = ibm_c^-1 * ibm_k, taken from its first shared
    // joint); its new joints get ibm_c = ibm_k * B_k^-1 so that all its joints agree on B_k and its
    // vertices can be moved into the canonical space by B_k (attach_meshes).
    out->inverse_bind_matrices.assign(n, glm::mat4(1.0f));
    std::vector<uint8_t> have_ibm(n, 0);
    for (size_t k = 0; k < model.skins.size(); ++k) {
        glm::mat4 offset(1.0f);
        for (size_t i = 0; i < set.raw_of_skin_joint[k].size(); ++i) {
            const auto j = static_cast<size_t>(set.raw_of_skin_joint[k][i]);
            if (!have_ibm[j]) continue;
            if (!(std::abs(glm::determinant(out->inverse_bind_matrices[j])) > 1e-12f))
                return make_error(file, "inverse bind matrix of joint nodes[" + std::to_string(skin_nodes[j]) + "] is singular", 0, 0, "skins");
            offset = glm::inverse(out->inverse_bind_matrices[j]) * set.skin_ibm[k][i];
            break;
        }
        const glm::mat4 undo = glm::inverse(offset);
        for (size_t i = 0; i < set.raw_of_skin_joint[k].size(); ++i) {
            const auto j = static_cast<size_t>(set.raw_of_skin_joint[k][i]);
            if (have_ibm[j]) continue;
            out->inverse_bind_matrices[j] = set.skin_ibm[k][i] * undo;
            have_ibm[j] = 1;
        }
    }

    set.bindings.resize(n);
    std::set<std::string> names;
    out->skeleton.joints.resize(n);
    for (size_t i = 0; i < n; ++i) {
        const int node = skin_nodes[i];
        const std::string where = "nodes[" + std::to_string(node) + "]";
        Result<glm::mat4> local = node_local_matrix(model, node, file);
        if (!local.ok()) return local.error();
        JointBinding& b = set.bindings[i];
        b.node = node;
        int p = parents[static_cast<size_t>(node)];
        while (p >= 0 && set.joint_of_node[static_cast<size_t>(p)] < 0) {  // fold non-joint ancestors
            Result<glm::mat4> pm = node_local_matrix(model, p, file);
            if (!pm.ok()) return pm.error();
            b.fold = pm.value() * b.fold;
            b.folded = true;
            b.chain.insert(b.chain.begin(), p);
            p = parents[static_cast<size_t>(p)];
        }
        if (b.folded) {
            Result<Trs> f = decompose(b.fold, file, where + " ancestors");
            if (!f.ok()) return f.error();
            const glm::vec3 s = glm::abs(f.value().s);
            if (std::abs(s.x - s.y) > 1e-5f * s.x || std::abs(s.x - s.z) > 1e-5f * s.x)
                out->notes.push_back(where + ": ancestors have non-uniform scale; folded animation keys are approximate");
        }
        Result<Trs> trs = decompose(b.fold * local.value(), file, where);
        if (!trs.ok()) return trs.error();
        RawJoint& j = out->skeleton.joints[i];
        const std::string& name = model.nodes[static_cast<size_t>(node)].name;
        j.name = name.empty() ? "node" + std::to_string(node) : name;
        if (!names.insert(j.name).second) {
            std::string unique = j.name + "_node" + std::to_string(node);
            for (int extra = 2; !names.insert(unique).second; ++extra) unique = j.name + "_node" + std::to_string(node) + "_" + std::to_string(extra);
            out->notes.push_back(where + ": duplicate joint name '" + j.name + "' renamed to '" + unique + "'");
            j.name = unique;
        }
        j.parent = p >= 0 ? set.joint_of_node[static_cast<size_t>(p)] : -1;
        j.translation = trs.value().t;
        j.rotation = trs.value().r;
        j.scale = trs.value().s;
    }
    return set;
}

}  // namespace aloha::gltf_detail
