// Mesh primitives of the glTF loader: positions, normals (read, or flat as the spec requires), joints
// (remapped to runtime order, up to 8 influences reduced to 4), normalised weights, texture coordinates
// (through the material's texture transform), default morph-target weights and triangle indices (lists,
// strips, fans), every value checked. Vertex data may be float or KHR_mesh_quantization's integer types.
#include "engine/assets/gltf_detail.hpp"

#include <algorithm>
#include <array>
#include <cmath>

namespace aloha::gltf_detail {

namespace {

constexpr int kFloat = TINYGLTF_COMPONENT_TYPE_FLOAT;
constexpr int kByte = TINYGLTF_COMPONENT_TYPE_BYTE;
constexpr int kShort = TINYGLTF_COMPONENT_TYPE_SHORT;
constexpr int kUByte = TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE;
constexpr int kUShort = TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT;
constexpr int kUInt = TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT;

// Triangle list of a primitive from its (possibly implicit) indices and mode (4 list, 5 strip, 6 fan),
// following the glTF spec's vertex order for strips and fans.
std::vector<uint32_t> to_triangle_list(const std::vector<uint32_t>& idx, int mode) {
    if (mode == TINYGLTF_MODE_TRIANGLES || mode == -1) return idx;
    std::vector<uint32_t> out;
    for (size_t i = 0; i + 2 < idx.size(); ++i) {
        if (mode == TINYGLTF_MODE_TRIANGLE_STRIP) {
            const size_t odd = i % 2;
            out.insert(out.end(), {idx[i], idx[i + 1 + odd], idx[i + 2 - odd]});
        } else {  // fan
            out.insert(out.end(), {idx[i + 1], idx[i + 2], idx[0]});
        }
    }
    return out;
}

// Gives every triangle its own three corners carrying its face normal (glTF: "When normals are not
// specified, client implementations MUST calculate flat normals"). Degenerate triangles point up.
void make_flat(GltfSkinnedMesh* m) {
    GltfSkinnedMesh f;
    const bool uv = !m->uvs.empty(), colour = !m->colours.empty();
    for (size_t t = 0; t + 2 < m->indices.size(); t += 3) {
        const glm::vec3 a = m->positions[m->indices[t]], b = m->positions[m->indices[t + 1]], c = m->positions[m->indices[t + 2]];
        const glm::vec3 cr = glm::cross(b - a, c - a);
        const glm::vec3 n = glm::length(cr) > 0.0f ? glm::normalize(cr) : glm::vec3(0, 1, 0);
        for (size_t k = 0; k < 3; ++k) {
            const uint32_t v = m->indices[t + k];
            f.indices.push_back(static_cast<uint32_t>(f.positions.size()));
            f.positions.push_back(m->positions[v]);
            f.normals.push_back(n);
            f.joints.push_back(m->joints[v]);
            f.weights.push_back(m->weights[v]);
            if (uv) f.uvs.push_back(m->uvs[v]);
            if (colour) f.colours.push_back(m->colours[v]);
        }
    }
    m->positions = std::move(f.positions);
    m->normals = std::move(f.normals);
    m->joints = std::move(f.joints);
    m->weights = std::move(f.weights);
    m->uvs = std::move(f.uvs);
    m->colours = std::move(f.colours);
    m->indices = std::move(f.indices);
}

// Largest allowed |sum - 1| of a vertex's weights: float noise, or the quantisation step of the
// normalised integer type per influence.
float weight_tolerance(const tinygltf::Model& model, int accessor, int influences) {
    const int c = model.accessors[static_cast<size_t>(accessor)].componentType;
    const float step = c == kUByte ? 1.0f / 255.0f : c == kUShort ? 1.0f / 65535.0f : 1e-4f;
    return step * static_cast<float>(influences);
}

// Component types of vertex data: the core spec's, widened by KHR_mesh_quantization (positions and texture
// coordinates of any integer type, normalised or not; normals and morph deltas of signed types).
const std::vector<int> kPositionTypes{kFloat, kByte, kUByte, kShort, kUShort};
const std::vector<int> kNormalTypes{kFloat, kByte, kShort};
const std::vector<int> kTexcoordTypes{kFloat, kByte, kUByte, kShort, kUShort};

bool uses_extension(const tinygltf::Model& model, const std::string& name) {
    return std::find(model.extensionsUsed.begin(), model.extensionsUsed.end(), name) != model.extensionsUsed.end() ||
           std::find(model.extensionsRequired.begin(), model.extensionsRequired.end(), name) != model.extensionsRequired.end();
}

class PrimitiveReader {
public:
    PrimitiveReader(const tinygltf::Model& model, const std::string& file, const std::string& where, MeshNotes* notes)
        : model_(model), file_(file), at_(where + ".attributes."), notes_(notes), quantized_(uses_extension(model, "KHR_mesh_quantization")) {}

    int attribute(const tinygltf::Primitive& prim, const std::string& name) const {
        const auto it = prim.attributes.find(name);
        return it == prim.attributes.end() ? -2 : it->second;
    }

    Status count_check(size_t count, size_t n, const std::string& name) const {
        if (count != n)
            return make_error(file_, name + " has " + std::to_string(count) + " elements but POSITION has " + std::to_string(n), 0, 0, at_ + name);
        return {};
    }

    // Joints and weights of a skinned primitive (JOINTS_0/WEIGHTS_0 and optionally the _1 sets).
    Status skin(const tinygltf::Primitive& prim, const std::vector<int>& runtime_of_skin_joint, GltfSkinnedMesh* mesh) const {
        const size_t n = mesh->positions.size();
        std::vector<uint32_t> joints;
        std::vector<float> weights;
        int sets = 0;
        float tolerance = 0.0f;
        for (int set = 0; set < 2; ++set) {
            const std::string js = "JOINTS_" + std::to_string(set), ws = "WEIGHTS_" + std::to_string(set);
            const int ja = attribute(prim, js), wa = attribute(prim, ws);
            if (ja == -2 || wa == -2) {
                if (set == 0) return make_error(file_, "skinned primitive has no " + (ja == -2 ? js : ws) + " attribute", 0, 0, at_.substr(0, at_.size() - 12));
                break;
            }
            Result<std::vector<uint32_t>> j = read_uints(model_, ja, TINYGLTF_TYPE_VEC4, {kUByte, kUShort}, file_, at_ + js);
            if (!j.ok()) return j.error();
            if (Status s = count_check(j.value().size() / 4, n, js); !s.ok()) return s;
            Result<std::vector<float>> w = read_floats(model_, wa, TINYGLTF_TYPE_VEC4, {kFloat, kUByte, kUShort}, file_, at_ + ws, true);
            if (!w.ok()) return w.error();
            if (Status s = count_check(w.value().size() / 4, n, ws); !s.ok()) return s;
            for (size_t v = 0; v < n * 4; ++v) {
                const uint32_t joint = j.value()[v];
                if (joint >= runtime_of_skin_joint.size())
                    return make_error(file_, "vertex " + std::to_string(v / 4) + " uses joint " + std::to_string(joint) + ", but the skin has " +
                                                 std::to_string(runtime_of_skin_joint.size()) + " joints", 0, 0, at_ + js);
                const float wv = w.value()[v];
                if (!std::isfinite(wv) || wv < 0.0f)
                    return make_error(file_, "vertex " + std::to_string(v / 4) + " has weight " + std::to_string(wv) + " (must be finite and >= 0)", 0, 0, at_ + ws);
            }
            tolerance += weight_tolerance(model_, wa, 4);
            ++sets;
            // Interleave per vertex: influences of set 0 then set 1.
            if (set == 0) {
                joints = std::move(j).value();
                weights = std::move(w).value();
            } else {
                std::vector<uint32_t> jj(n * 8);
                std::vector<float> ww(n * 8);
                for (size_t v = 0; v < n; ++v)
                    for (size_t k = 0; k < 4; ++k) {
                        jj[v * 8 + k] = joints[v * 4 + k], ww[v * 8 + k] = weights[v * 4 + k];
                        jj[v * 8 + 4 + k] = j.value()[v * 4 + k], ww[v * 8 + 4 + k] = w.value()[v * 4 + k];
                    }
                joints = std::move(jj);
                weights = std::move(ww);
            }
        }
        const size_t per = static_cast<size_t>(sets) * 4;
        if (sets > 1) ++notes_->eight_influence_primitives;
        mesh->joints.resize(n);
        mesh->weights.resize(n);
        size_t unnormalised = 0;
        for (size_t v = 0; v < n; ++v) {
            std::array<size_t, 8> order{0, 1, 2, 3, 4, 5, 6, 7};
            std::stable_sort(order.begin(), order.begin() + static_cast<long>(per),
                             [&](size_t a, size_t b) { return weights[v * per + a] > weights[v * per + b]; });
            float all = 0.0f, kept = 0.0f;
            for (size_t k = 0; k < per; ++k) all += weights[v * per + k];
            glm::vec4 w(0.0f);
            for (int k = 0; k < 4; ++k) {
                const size_t s = v * per + order[static_cast<size_t>(k)];
                mesh->joints[v][k] = static_cast<uint16_t>(runtime_of_skin_joint[joints[s]]);
                w[k] = weights[s];
                kept += weights[s];
            }
            if (!(kept > 0.0f)) return make_error(file_, "vertex " + std::to_string(v) + " has all-zero weights", 0, 0, at_ + "WEIGHTS_0");
            if (std::abs(all - 1.0f) > tolerance) ++unnormalised;
            mesh->weights[v] = w / kept;
        }
        if (unnormalised > 0) {
            notes_->unnormalised_vertices += unnormalised;
            ++notes_->unnormalised_primitives;
        }
        return {};
    }

    // Texture coordinates TEXCOORD_<set>, through the material's texture transform. Integer coordinates are
    // normalised as the core spec requires them to be, unless the file uses KHR_mesh_quantization, which
    // allows unnormalised ones (its accessors then say which).
    Status uvs(const tinygltf::Primitive& prim, const MaterialUv& material, GltfSkinnedMesh* mesh) const {
        const std::string name = "TEXCOORD_" + std::to_string(material.texcoord);
        const int a = attribute(prim, name);
        if (a == -2) {
            ++notes_->untextured_primitives;
            return {};
        }
        Result<std::vector<float>> uv = read_floats(model_, a, TINYGLTF_TYPE_VEC2, quantized_ ? kTexcoordTypes : std::vector<int>{kFloat, kUByte, kUShort},
                                                    file_, at_ + name, !quantized_);
        if (!uv.ok()) return uv.error();
        if (Status s = count_check(uv.value().size() / 2, mesh->positions.size(), name); !s.ok()) return s;
        mesh->uvs.resize(mesh->positions.size());
        for (size_t v = 0; v < mesh->uvs.size(); ++v) {
            mesh->uvs[v] = glm::vec2(material.transform * glm::vec3(uv.value()[2 * v], uv.value()[2 * v + 1], 1.0f));
            if (!std::isfinite(mesh->uvs[v].x + mesh->uvs[v].y))
                return make_error(file_, "vertex " + std::to_string(v) + " texture coordinate is NaN or infinite", 0, 0, at_ + name);
        }
        return {};
    }

    // COLOR_0 (VEC3 or VEC4; float, or normalised unsigned byte or short): linear colours in [0, 1], alpha 1
    // for VEC3. Nothing when the primitive has none.
    Status colours(const tinygltf::Primitive& prim, GltfSkinnedMesh* mesh) const {
        const int a = attribute(prim, "COLOR_0");
        if (a == -2) return {};
        if (a < 0 || static_cast<size_t>(a) >= model_.accessors.size())
            return make_error(file_, "accessor " + std::to_string(a) + " is out of range", 0, 0, at_ + "COLOR_0");
        const int type = model_.accessors[static_cast<size_t>(a)].type;
        if (type != TINYGLTF_TYPE_VEC3 && type != TINYGLTF_TYPE_VEC4)
            return make_error(file_, "COLOR_0 must be VEC3 or VEC4", 0, 0, at_ + "COLOR_0");
        Result<std::vector<float>> c = read_floats(model_, a, type, {kFloat, kUByte, kUShort}, file_, at_ + "COLOR_0", /*force_normalize=*/true);
        if (!c.ok()) return c.error();
        const size_t k = type == TINYGLTF_TYPE_VEC3 ? 3 : 4;
        if (Status s = count_check(c.value().size() / k, mesh->positions.size(), "COLOR_0"); !s.ok()) return s;
        mesh->colours.resize(mesh->positions.size());
        for (size_t v = 0; v < mesh->colours.size(); ++v) {
            glm::vec4 out(1.0f);
            for (size_t i = 0; i < k; ++i) out[static_cast<int>(i)] = c.value()[k * v + i];
            if (!std::isfinite(out.r + out.g + out.b + out.a))
                return make_error(file_, "vertex " + std::to_string(v) + " colour is NaN or infinite", 0, 0, at_ + "COLOR_0");
            mesh->colours[v] = glm::clamp(out, 0.0f, 1.0f);
        }
        ++notes_->coloured_primitives;
        return {};
    }

    // Adds weight * target attribute `name` of every morph target with a non-zero default weight.
    Status morph(const tinygltf::Primitive& prim, const std::vector<double>* weights, const std::string& name,
                 std::vector<glm::vec3>* values, bool* applied) const {
        for (size_t t = 0; t < prim.targets.size(); ++t) {
            const double w = weights && t < weights->size() ? (*weights)[t] : 0.0;
            if (!std::isfinite(w)) return make_error(file_, "default morph weight " + std::to_string(t) + " is NaN or infinite", 0, 0, at_);
            const auto it = prim.targets[t].find(name);
            if (w == 0.0 || it == prim.targets[t].end()) continue;
            const std::string usage = at_.substr(0, at_.size() - 12) + ".targets[" + std::to_string(t) + "]." + name;
            Result<std::vector<float>> d = read_floats(model_, it->second, TINYGLTF_TYPE_VEC3, kNormalTypes, file_, usage);
            if (!d.ok()) return d.error();
            if (Status s = count_check(d.value().size() / 3, values->size(), usage); !s.ok()) return s;
            for (size_t v = 0; v < values->size(); ++v)
                (*values)[v] += static_cast<float>(w) * glm::vec3(d.value()[3 * v], d.value()[3 * v + 1], d.value()[3 * v + 2]);
            *applied = true;
        }
        return {};
    }

private:
    const tinygltf::Model& model_;
    const std::string& file_;
    std::string at_;
    MeshNotes* notes_;
    bool quantized_;
};

// Reads one primitive; returns false (with a count in `notes`) for points and lines.
Result<bool> read_primitive(const tinygltf::Model& model, const tinygltf::Primitive& prim, const std::string& where,
                            const PrimitiveBinding& binding, const std::vector<SurfaceMaterial>& materials,
                            const std::vector<MaterialUv>& material_uv, const std::string& file, MeshNotes* notes,
                            GltfSkinnedMesh* mesh) {
    if (prim.mode >= TINYGLTF_MODE_POINTS && prim.mode <= TINYGLTF_MODE_LINE_STRIP) {
        ++notes->skipped_primitives;
        return false;
    }
    if (prim.mode != TINYGLTF_MODE_TRIANGLES && prim.mode != TINYGLTF_MODE_TRIANGLE_STRIP && prim.mode != TINYGLTF_MODE_TRIANGLE_FAN && prim.mode != -1)
        return make_error(file, "primitive mode " + std::to_string(prim.mode) + " is not a glTF mode (0-6)", 0, 0, where);
    PrimitiveReader r(model, file, where, notes);
    const std::string at = where + ".attributes.";
    if (r.attribute(prim, "POSITION") == -2) return make_error(file, "primitive has no POSITION attribute", 0, 0, where);
    Result<std::vector<float>> pos = read_floats(model, r.attribute(prim, "POSITION"), TINYGLTF_TYPE_VEC3, kPositionTypes, file, at + "POSITION");
    if (!pos.ok()) return pos.error();
    const size_t n = pos.value().size() / 3;
    mesh->positions.resize(n);
    for (size_t v = 0; v < n; ++v) {
        mesh->positions[v] = glm::vec3(pos.value()[3 * v], pos.value()[3 * v + 1], pos.value()[3 * v + 2]);
        if (!std::isfinite(mesh->positions[v].x + mesh->positions[v].y + mesh->positions[v].z))
            return make_error(file, "vertex " + std::to_string(v) + " position is NaN or infinite", 0, 0, at + "POSITION");
    }
    bool morphed = false;
    if (!prim.targets.empty()) {
        ++notes->morph_primitives;
        if (Status s = r.morph(prim, binding.morph_weights, "POSITION", &mesh->positions, &morphed); !s.ok()) return s.error();
    }

    if (binding.runtime_of_skin_joint) {
        if (Status s = r.skin(prim, *binding.runtime_of_skin_joint, mesh); !s.ok()) return s.error();
    } else {
        mesh->joints.assign(n, glm::u16vec4(binding.rigid_joint, 0, 0, 0));
        mesh->weights.assign(n, glm::vec4(1.0f, 0.0f, 0.0f, 0.0f));
    }

    std::vector<uint32_t> idx;
    if (prim.indices >= 0) {
        Result<std::vector<uint32_t>> read = read_uints(model, prim.indices, TINYGLTF_TYPE_SCALAR, {kUByte, kUShort, kUInt}, file, where + ".indices");
        if (!read.ok()) return read.error();
        idx = std::move(read).value();
    } else {
        idx.resize(n);
        for (size_t v = 0; v < n; ++v) idx[v] = static_cast<uint32_t>(v);
    }
    for (size_t k = 0; k < idx.size(); ++k)
        if (idx[k] >= n)
            return make_error(file, "index " + std::to_string(k) + " is " + std::to_string(idx[k]) + ", but there are " + std::to_string(n) + " vertices", 0, 0,
                              where + ".indices");
    const int mode = prim.mode;
    if ((mode == TINYGLTF_MODE_TRIANGLES || mode == -1) && idx.size() % 3 != 0)
        return make_error(file, "triangle list has " + std::to_string(idx.size()) + " indices, not a multiple of 3", 0, 0, where + ".indices");
    mesh->indices = to_triangle_list(idx, mode);

    if (prim.material >= static_cast<int>(materials.size()))
        return make_error(file, "material " + std::to_string(prim.material) + " is out of range (the file has " + std::to_string(materials.size()) + " materials)", 0, 0,
                          where + ".material");
    mesh->material = prim.material;
    if (Status s = r.colours(prim, mesh); !s.ok()) return s.error();
    if (prim.material >= 0 && material_uv[static_cast<size_t>(prim.material)].texcoord >= 0)
        if (Status s = r.uvs(prim, material_uv[static_cast<size_t>(prim.material)], mesh); !s.ok()) return s.error();

    if (r.attribute(prim, "NORMAL") != -2) {
        Result<std::vector<float>> nrm = read_floats(model, r.attribute(prim, "NORMAL"), TINYGLTF_TYPE_VEC3, kNormalTypes, file, at + "NORMAL");
        if (!nrm.ok()) return nrm.error();
        if (Status s = r.count_check(nrm.value().size() / 3, n, "NORMAL"); !s.ok()) return s.error();
        mesh->normals.resize(n);
        for (size_t v = 0; v < n; ++v) mesh->normals[v] = glm::vec3(nrm.value()[3 * v], nrm.value()[3 * v + 1], nrm.value()[3 * v + 2]);
        if (!prim.targets.empty())
            if (Status s = r.morph(prim, binding.morph_weights, "NORMAL", &mesh->normals, &morphed); !s.ok()) return s.error();
        for (size_t v = 0; v < n; ++v) {
            const float len = glm::length(mesh->normals[v]);
            if (!std::isfinite(len) || len < 1e-6f)
                return make_error(file, "vertex " + std::to_string(v) + " normal is zero, NaN or infinite", 0, 0, at + "NORMAL");
            mesh->normals[v] /= len;
        }
    } else {
        ++notes->flat_normal_primitives;
        make_flat(mesh);
    }
    if (morphed) ++notes->morph_applied_primitives;
    return true;
}

}  // namespace

Status read_mesh(const tinygltf::Model& model, int node_index, int mesh_index, const PrimitiveBinding& binding,
                 const std::vector<SurfaceMaterial>& materials, const std::vector<MaterialUv>& material_uv,
                 const std::string& file, MeshNotes* notes, std::vector<GltfSkinnedMesh>* out) {
    const std::string where = "meshes[" + std::to_string(mesh_index) + "]";
    if (mesh_index < 0 || static_cast<size_t>(mesh_index) >= model.meshes.size())
        return make_error(file, "mesh index is out of range (the file has " + std::to_string(model.meshes.size()) + " meshes)", 0, 0,
                          "nodes[" + std::to_string(node_index) + "]");
    const tinygltf::Mesh& mesh = model.meshes[static_cast<size_t>(mesh_index)];
    for (size_t p = 0; p < mesh.primitives.size(); ++p) {
        GltfSkinnedMesh m;
        const std::string pw = where + ".primitives[" + std::to_string(p) + "]";
        Result<bool> read = read_primitive(model, mesh.primitives[p], pw, binding, materials, material_uv, file, notes, &m);
        if (!read.ok()) return read.error();
        if (!read.value()) continue;
        m.source = "nodes[" + std::to_string(node_index) + "] " + pw;
        out->push_back(std::move(m));
    }
    return {};
}

}  // namespace aloha::gltf_detail
