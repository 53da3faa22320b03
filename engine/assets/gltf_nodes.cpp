// Node hierarchy checks and transform helpers for the glTF loader.
#include "engine/anim/pose.hpp"
#include "engine/assets/gltf_detail.hpp"

#include <glm/gtc/type_ptr.hpp>

#include <cmath>

namespace aloha::gltf_detail {

namespace {
std::string node_path(size_t i) { return "nodes[" + std::to_string(i) + "]"; }
}  // namespace

Result<std::vector<int>> node_parents(const tinygltf::Model& model, const std::string& file) {
    const size_t n = model.nodes.size();
    std::vector<int> parent(n, -1);
    for (size_t i = 0; i < n; ++i) {
        for (int c : model.nodes[i].children) {
            if (c < 0 || static_cast<size_t>(c) >= n)
                return make_error(file, "child index " + std::to_string(c) + " is out of range (the file has " + std::to_string(n) + " nodes)", 0, 0, node_path(i));
            if (static_cast<size_t>(c) == i) return make_error(file, "node lists itself as a child (cyclic hierarchy)", 0, 0, node_path(i));
            if (parent[static_cast<size_t>(c)] != -1)
                return make_error(file, "node " + std::to_string(c) + " has more than one parent (nodes " +
                                            std::to_string(parent[static_cast<size_t>(c)]) + " and " + std::to_string(i) + ")", 0, 0, node_path(i));
            parent[static_cast<size_t>(c)] = static_cast<int>(i);
        }
    }
    // With one parent per node, a cycle is a loop of parent links: walk up at most n steps.
    for (size_t i = 0; i < n; ++i) {
        int p = parent[i];
        size_t steps = 0;
        while (p >= 0 && steps <= n) {
            p = parent[static_cast<size_t>(p)];
            ++steps;
        }
        if (steps > n) return make_error(file, "node hierarchy has a cycle through this node", 0, 0, node_path(i));
    }
    return parent;
}

Result<glm::mat4> node_local_matrix(const tinygltf::Model& model, int index, const std::string& file) {
    const tinygltf::Node& node = model.nodes[static_cast<size_t>(index)];
    const std::string where = node_path(static_cast<size_t>(index));
    auto finite = [](const std::vector<double>& v) {
        for (double d : v)
            if (!std::isfinite(d)) return false;
        return true;
    };
    if (!node.matrix.empty()) {
        if (node.matrix.size() != 16) return make_error(file, "matrix has " + std::to_string(node.matrix.size()) + " values, expected 16", 0, 0, where);
        if (!finite(node.matrix)) return make_error(file, "matrix has a NaN or infinite value", 0, 0, where);
        glm::mat4 m(1.0f);
        for (int c = 0; c < 4; ++c)
            for (int r = 0; r < 4; ++r) m[c][r] = static_cast<float>(node.matrix[static_cast<size_t>(c * 4 + r)]);
        return m;
    }
    const struct {
        const std::vector<double>* v;
        size_t n;
        const char* name;
    } parts[3] = {{&node.translation, 3, "translation"}, {&node.rotation, 4, "rotation"}, {&node.scale, 3, "scale"}};
    for (const auto& p : parts) {
        if (!p.v->empty() && p.v->size() != p.n)
            return make_error(file, std::string(p.name) + " has " + std::to_string(p.v->size()) + " values, expected " + std::to_string(p.n), 0, 0, where);
        if (!finite(*p.v)) return make_error(file, std::string(p.name) + " has a NaN or infinite value", 0, 0, where);
    }
    glm::vec3 t(0.0f), s(1.0f);
    glm::quat r(1.0f, 0.0f, 0.0f, 0.0f);
    if (!node.translation.empty()) t = glm::vec3(node.translation[0], node.translation[1], node.translation[2]);
    if (!node.scale.empty()) s = glm::vec3(node.scale[0], node.scale[1], node.scale[2]);
    if (!node.rotation.empty()) {
        r = glm::quat(static_cast<float>(node.rotation[3]), static_cast<float>(node.rotation[0]),
                      static_cast<float>(node.rotation[1]), static_cast<float>(node.rotation[2]));
        if (glm::length(r) < 1e-6f) return make_error(file, "rotation quaternion has zero length", 0, 0, where);
        r = glm::normalize(r);
    }
    return trs_matrix(t, r, s);
}

Result<Trs> decompose(const glm::mat4& m, const std::string& file, const std::string& where) {
    Trs out;
    out.t = glm::vec3(m[3]);
    glm::vec3 c[3] = {glm::vec3(m[0]), glm::vec3(m[1]), glm::vec3(m[2])};
    for (int i = 0; i < 3; ++i) {
        out.s[i] = glm::length(c[i]);
        if (!(out.s[i] > 1e-8f)) return make_error(file, "transform is singular (zero scale)", 0, 0, where);
        c[i] /= out.s[i];
    }
    // Column dot products of a rotation are 0; float products of unit vectors carry ~1e-7 error,
    // so 1e-4 only rejects real shear.
    if (std::abs(glm::dot(c[0], c[1])) > 1e-4f || std::abs(glm::dot(c[0], c[2])) > 1e-4f || std::abs(glm::dot(c[1], c[2])) > 1e-4f)
        return make_error(file, "transform has shear, which a joint transform cannot represent", 0, 0, where);
    if (glm::dot(glm::cross(c[0], c[1]), c[2]) < 0.0f) {  // mirrored: put the sign in the scale
        out.s.x = -out.s.x;
        c[0] = -c[0];
    }
    out.r = glm::normalize(glm::quat_cast(glm::mat3(c[0], c[1], c[2])));
    if (std::abs(m[0][3]) > 1e-6f || std::abs(m[1][3]) > 1e-6f || std::abs(m[2][3]) > 1e-6f || std::abs(m[3][3] - 1.0f) > 1e-6f)
        return make_error(file, "matrix is not affine (last row is not 0 0 0 1)", 0, 0, where);
    return out;
}

}  // namespace aloha::gltf_detail
