// Skinned mesh primitives of the glTF loader: positions, normals, joints (remapped to runtime
// order), normalised weights and triangle indices, every value checked.
#include "engine/assets/gltf_detail.hpp"

#include <cmath>

namespace aloha::gltf_detail {

namespace {

constexpr int kFloat = TINYGLTF_COMPONENT_TYPE_FLOAT;
constexpr int kUByte = TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE;
constexpr int kUShort = TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT;
constexpr int kUInt = TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT;

// Area-weighted vertex normals (cross products are proportional to triangle area).
std::vector<glm::vec3> compute_normals(const std::vector<glm::vec3>& p, const std::vector<uint32_t>& idx) {
    std::vector<glm::vec3> n(p.size(), glm::vec3(0.0f));
    for (size_t t = 0; t + 2 < idx.size(); t += 3) {
        const glm::vec3 f = glm::cross(p[idx[t + 1]] - p[idx[t]], p[idx[t + 2]] - p[idx[t]]);
        for (size_t k = 0; k < 3; ++k) n[idx[t + k]] += f;
    }
    for (glm::vec3& v : n) v = glm::length(v) > 0.0f ? glm::normalize(v) : glm::vec3(0, 1, 0);
    return n;
}

Status read_primitive(const tinygltf::Model& model, const tinygltf::Primitive& prim, const std::string& where,
                      const std::vector<int>& runtime_of_raw, const std::string& file, GltfSkinnedMesh* mesh) {
    if (prim.mode != TINYGLTF_MODE_TRIANGLES && prim.mode != -1)
        return make_error(file, "primitive mode " + std::to_string(prim.mode) + " is not supported (only TRIANGLES, 4)", 0, 0, where);
    auto attribute = [&](const char* name) {
        const auto it = prim.attributes.find(name);
        return it == prim.attributes.end() ? -2 : it->second;
    };
    for (const char* required : {"POSITION", "JOINTS_0", "WEIGHTS_0"})
        if (attribute(required) == -2) return make_error(file, std::string("skinned primitive has no ") + required + " attribute", 0, 0, where);
    const std::string at = where + ".attributes.";

    Result<std::vector<float>> pos = read_floats(model, attribute("POSITION"), TINYGLTF_TYPE_VEC3, {kFloat}, file, at + "POSITION");
    if (!pos.ok()) return pos.error();
    const size_t n = pos.value().size() / 3;
    mesh->positions.resize(n);
    for (size_t v = 0; v < n; ++v) {
        mesh->positions[v] = glm::vec3(pos.value()[3 * v], pos.value()[3 * v + 1], pos.value()[3 * v + 2]);
        if (!std::isfinite(mesh->positions[v].x + mesh->positions[v].y + mesh->positions[v].z))
            return make_error(file, "vertex " + std::to_string(v) + " position is NaN or infinite", 0, 0, at + "POSITION");
    }
    auto count_check = [&](size_t count, const char* name) -> Status {
        if (count != n)
            return make_error(file, std::string(name) + " has " + std::to_string(count) + " elements but POSITION has " + std::to_string(n), 0, 0, at + name);
        return {};
    };

    Result<std::vector<uint32_t>> joints = read_uints(model, attribute("JOINTS_0"), TINYGLTF_TYPE_VEC4, {kUByte, kUShort}, file, at + "JOINTS_0");
    if (!joints.ok()) return joints.error();
    if (Status s = count_check(joints.value().size() / 4, "JOINTS_0"); !s.ok()) return s;
    Result<std::vector<float>> weights = read_floats(model, attribute("WEIGHTS_0"), TINYGLTF_TYPE_VEC4, {kFloat, kUByte, kUShort}, file, at + "WEIGHTS_0", true);
    if (!weights.ok()) return weights.error();
    if (Status s = count_check(weights.value().size() / 4, "WEIGHTS_0"); !s.ok()) return s;
    mesh->joints.resize(n);
    mesh->weights.resize(n);
    for (size_t v = 0; v < n; ++v) {
        glm::vec4 w(0.0f);
        for (int k = 0; k < 4; ++k) {
            const uint32_t j = joints.value()[4 * v + static_cast<size_t>(k)];
            if (j >= runtime_of_raw.size())
                return make_error(file, "vertex " + std::to_string(v) + " uses joint " + std::to_string(j) + ", but the skin has " +
                                            std::to_string(runtime_of_raw.size()) + " joints", 0, 0, at + "JOINTS_0");
            mesh->joints[v][k] = static_cast<uint16_t>(runtime_of_raw[j]);
            w[k] = weights.value()[4 * v + static_cast<size_t>(k)];
            if (!std::isfinite(w[k]) || w[k] < 0.0f)
                return make_error(file, "vertex " + std::to_string(v) + " has weight " + std::to_string(w[k]) + " (must be finite and >= 0)", 0, 0, at + "WEIGHTS_0");
        }
        const float sum = w.x + w.y + w.z + w.w;
        if (!(sum > 0.0f)) return make_error(file, "vertex " + std::to_string(v) + " has all-zero weights", 0, 0, at + "WEIGHTS_0");
        mesh->weights[v] = w / sum;
    }

    if (prim.indices >= 0) {
        Result<std::vector<uint32_t>> idx = read_uints(model, prim.indices, TINYGLTF_TYPE_SCALAR, {kUByte, kUShort, kUInt}, file, where + ".indices");
        if (!idx.ok()) return idx.error();
        mesh->indices = std::move(idx).value();
    } else {
        mesh->indices.resize(n);
        for (size_t v = 0; v < n; ++v) mesh->indices[v] = static_cast<uint32_t>(v);
    }
    if (mesh->indices.size() % 3 != 0)
        return make_error(file, "triangle list has " + std::to_string(mesh->indices.size()) + " indices, not a multiple of 3", 0, 0, where + ".indices");
    for (size_t k = 0; k < mesh->indices.size(); ++k)
        if (mesh->indices[k] >= n)
            return make_error(file, "index " + std::to_string(k) + " is " + std::to_string(mesh->indices[k]) + ", but there are " +
                                        std::to_string(n) + " vertices", 0, 0, where + ".indices");

    if (attribute("NORMAL") != -2) {
        Result<std::vector<float>> nrm = read_floats(model, attribute("NORMAL"), TINYGLTF_TYPE_VEC3, {kFloat}, file, at + "NORMAL");
        if (!nrm.ok()) return nrm.error();
        if (Status s = count_check(nrm.value().size() / 3, "NORMAL"); !s.ok()) return s;
        mesh->normals.resize(n);
        for (size_t v = 0; v < n; ++v) {
            const glm::vec3 nv(nrm.value()[3 * v], nrm.value()[3 * v + 1], nrm.value()[3 * v + 2]);
            const float len = glm::length(nv);
            if (!std::isfinite(len) || len < 1e-6f)
                return make_error(file, "vertex " + std::to_string(v) + " normal is zero, NaN or infinite", 0, 0, at + "NORMAL");
            mesh->normals[v] = nv / len;
        }
    } else {
        mesh->normals = compute_normals(mesh->positions, mesh->indices);
    }
    return {};
}

}  // namespace

Status read_skinned_mesh(const tinygltf::Model& model, int mesh_index, const std::vector<int>& runtime_of_raw,
                         const std::string& file, std::vector<GltfSkinnedMesh>* out) {
    const std::string where = "meshes[" + std::to_string(mesh_index) + "]";
    if (mesh_index < 0 || static_cast<size_t>(mesh_index) >= model.meshes.size())
        return make_error(file, "mesh index is out of range (the file has " + std::to_string(model.meshes.size()) + " meshes)", 0, 0, where);
    const tinygltf::Mesh& mesh = model.meshes[static_cast<size_t>(mesh_index)];
    for (size_t p = 0; p < mesh.primitives.size(); ++p) {
        GltfSkinnedMesh m;
        if (Status s = read_primitive(model, mesh.primitives[p], where + ".primitives[" + std::to_string(p) + "]", runtime_of_raw, file, &m); !s.ok())
            return s;
        out->push_back(std::move(m));
    }
    return {};
}

}  // namespace aloha::gltf_detail
