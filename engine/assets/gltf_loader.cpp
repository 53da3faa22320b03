// glTF character loader: runs tinygltf, then checks and converts skin 0, its meshes and clips.
#include "engine/assets/gltf_loader.hpp"

#include "engine/core/json_depth.hpp"

#include "engine/anim/skeleton.hpp"
#include "engine/assets/animation_remap.hpp"
#include "engine/assets/file_io.hpp"
#include "engine/assets/gltf_detail.hpp"

#include <cmath>
#include <exception>
#include <filesystem>
#include <limits>
#include <set>

namespace aloha {

namespace {

using namespace gltf_detail;

// Images are not needed by the character loader: accept them without decoding.
bool skip_image(tinygltf::Image*, const int, std::string*, std::string*, int, int, const unsigned char*, int, void*) {
    return true;
}

Result<GltfCharacter> convert(const tinygltf::Model& model, const std::string& file) {
    if (model.skins.empty()) return make_error(file, "file has no skins (a character needs skin 0)", 0, 0, "skins");
    const tinygltf::Skin& skin = model.skins[0];
    const size_t n = skin.joints.size();
    if (n == 0) return make_error(file, "skin has no joints", 0, 0, "skins[0]");
    if (n > 32767) return make_error(file, "skin has " + std::to_string(n) + " joints; at most 32767 are supported", 0, 0, "skins[0]");
    Result<std::vector<int>> parents_r = node_parents(model, file);
    if (!parents_r.ok()) return parents_r.error();
    const std::vector<int>& parents = parents_r.value();
    std::vector<int> joint_of_node(model.nodes.size(), -1);
    for (size_t i = 0; i < n; ++i) {
        const int node = skin.joints[i];
        const std::string where = "skins[0].joints[" + std::to_string(i) + "]";
        if (node < 0 || static_cast<size_t>(node) >= model.nodes.size())
            return make_error(file, "node " + std::to_string(node) + " is out of range (the file has " + std::to_string(model.nodes.size()) + " nodes)", 0, 0, where);
        if (joint_of_node[static_cast<size_t>(node)] >= 0)
            return make_error(file, "nodes[" + std::to_string(node) + "] is listed twice in the skin", 0, 0, where);
        joint_of_node[static_cast<size_t>(node)] = static_cast<int>(i);
    }

    GltfCharacter out;
    std::vector<JointBinding> bindings(n);
    std::set<std::string> names;
    out.skeleton.joints.resize(n);
    for (size_t i = 0; i < n; ++i) {
        const int node = skin.joints[i];
        const std::string where = "nodes[" + std::to_string(node) + "]";
        Result<glm::mat4> local = node_local_matrix(model, node, file);
        if (!local.ok()) return local.error();
        JointBinding& b = bindings[i];
        b.node = node;
        int p = parents[static_cast<size_t>(node)];
        while (p >= 0 && joint_of_node[static_cast<size_t>(p)] < 0) {  // fold non-joint ancestors
            Result<glm::mat4> pm = node_local_matrix(model, p, file);
            if (!pm.ok()) return pm.error();
            b.fold = pm.value() * b.fold;
            b.folded = true;
            p = parents[static_cast<size_t>(p)];
        }
        if (b.folded) {
            Result<Trs> f = decompose(b.fold, file, where + " ancestors");
            if (!f.ok()) return f.error();
            const glm::vec3 s = glm::abs(f.value().s);
            if (std::abs(s.x - s.y) > 1e-5f * s.x || std::abs(s.x - s.z) > 1e-5f * s.x)
                out.notes.push_back(where + ": ancestors have non-uniform scale; folded animation keys are approximate");
        }
        Result<Trs> trs = decompose(b.fold * local.value(), file, where);
        if (!trs.ok()) return trs.error();
        RawJoint& j = out.skeleton.joints[i];
        j.name = model.nodes[static_cast<size_t>(node)].name.empty() ? "node" + std::to_string(node) : model.nodes[static_cast<size_t>(node)].name;
        if (!names.insert(j.name).second) {
            out.notes.push_back(where + ": duplicate joint name '" + j.name + "' renamed to '" + j.name + "_node" + std::to_string(node) + "'");
            j.name += "_node" + std::to_string(node);
        }
        j.parent = p >= 0 ? joint_of_node[static_cast<size_t>(p)] : -1;
        j.translation = trs.value().t;
        j.rotation = trs.value().r;
        j.scale = trs.value().s;
    }

    out.inverse_bind_matrices.assign(n, glm::mat4(1.0f));
    if (skin.inverseBindMatrices >= 0) {
        Result<std::vector<float>> ibm = read_floats(model, skin.inverseBindMatrices, TINYGLTF_TYPE_MAT4,
                                                     {TINYGLTF_COMPONENT_TYPE_FLOAT}, file, "skins[0].inverseBindMatrices");
        if (!ibm.ok()) return ibm.error();
        if (ibm.value().size() < n * 16)
            return make_error(file, "has " + std::to_string(ibm.value().size() / 16) + " matrices for " + std::to_string(n) + " joints", 0, 0,
                              "accessors[" + std::to_string(skin.inverseBindMatrices) + "]");
        for (size_t i = 0; i < n; ++i)
            for (int c = 0; c < 4; ++c)
                for (int r = 0; r < 4; ++r) {
                    const float v = ibm.value()[i * 16 + static_cast<size_t>(c * 4 + r)];
                    if (!std::isfinite(v))
                        return make_error(file, "inverse bind matrix " + std::to_string(i) + " has a NaN or infinite value", 0, 0,
                                          "accessors[" + std::to_string(skin.inverseBindMatrices) + "]");
                    out.inverse_bind_matrices[i][c][r] = v;
                }
    }

    Result<Skeleton> skeleton = build_skeleton(out.skeleton, file);
    if (!skeleton.ok()) return skeleton.error();
    const std::vector<int> runtime_of_raw = runtime_index_of_raw(skeleton.value());

    for (size_t i = 0; i < model.nodes.size(); ++i) {
        const tinygltf::Node& node = model.nodes[i];
        if (node.skin >= 0 && static_cast<size_t>(node.skin) >= model.skins.size())
            return make_error(file, "skin " + std::to_string(node.skin) + " is out of range (the file has " + std::to_string(model.skins.size()) + " skins)", 0, 0,
                              "nodes[" + std::to_string(i) + "]");
        if (node.mesh < 0) continue;
        if (node.skin != 0) {
            out.notes.push_back("nodes[" + std::to_string(i) + "]: mesh not skinned by skin 0; ignored");
            continue;
        }
        if (Status s = read_skinned_mesh(model, node.mesh, runtime_of_raw, file, &out.meshes); !s.ok()) return s.error();
    }

    for (size_t a = 0; a < model.animations.size(); ++a) {
        Result<RawAnimation> clip = read_clip(model, static_cast<int>(a), bindings, file, &out.notes);
        if (!clip.ok()) return clip.error();
        out.clips.push_back(remap_to_runtime(clip.value(), skeleton.value()));
        out.clip_names.push_back(out.clips.back().name);
    }
    return out;
}

// External buffers may only come from the character's own folder (no "../secret.bin", no absolute
// paths elsewhere): tinygltf's file callbacks are wrapped with a containment check on real paths.
struct FolderGuard {
    std::filesystem::path folder;  // weakly canonical
    bool inside(const std::string& path) const {
        std::error_code ec;
        const auto p = std::filesystem::weakly_canonical(std::filesystem::absolute(path, ec), ec);
        if (ec) return false;
        auto f = folder.begin();
        auto q = p.begin();
        for (; f != folder.end() && !f->empty(); ++f, ++q)
            if (q == p.end() || *f != *q) return false;
        return true;
    }
};

bool guarded_exists(const std::string& path, void* user) {
    // Outside paths are reported by guarded_read (with a clear message), not as "file not found".
    return !static_cast<FolderGuard*>(user)->inside(path) || tinygltf::FileExists(path, nullptr);
}

bool guarded_read(std::vector<unsigned char>* out, std::string* err, const std::string& path, void* user) {
    if (!static_cast<FolderGuard*>(user)->inside(path)) {
        if (err) {
            if (!tinygltf::FileExists(path, nullptr)) *err += "buffer file '" + path + "' not found\n";
            else *err += "refusing to read '" + path + "': it escapes the glTF file's folder\n";
        }
        return false;
    }
    return tinygltf::ReadWholeFile(out, err, path, nullptr);
}

bool refuse_write(std::string* err, const std::string&, const std::vector<unsigned char>&, void*) {
    if (err) *err += "writing files is not supported\n";
    return false;
}

// Runs tinygltf on `bytes` (GLB when it starts with "glTF", JSON otherwise) and converts.
Result<GltfCharacter> load_from_memory(const unsigned char* bytes, size_t size, const std::string& file, const std::string& base_dir) {
    if (size > std::numeric_limits<unsigned int>::max()) return make_error(file, "file is too large for tinygltf");
    const bool is_glb = size >= 4 && bytes[0] == 'g' && bytes[1] == 'l' && bytes[2] == 'T' && bytes[3] == 'F';
    {
        // tinygltf converts JSON recursively: refuse hostile nesting before it sees the text.
        size_t begin = 0, length = size;
        if (is_glb) {
            begin = 20;
            length = size >= 20 ? (size_t{bytes[12]} | size_t{bytes[13]} << 8 | size_t{bytes[14]} << 16 | size_t{bytes[15]} << 24) : 0;
            length = std::min(length, size >= 20 ? size - 20 : 0);
        }
        if (Status deep = check_json_depth(std::string_view(reinterpret_cast<const char*>(bytes) + begin, length), file); !deep.ok())
            return deep.error();
    }
    FolderGuard guard;
    {
        std::error_code ec;
        guard.folder = std::filesystem::weakly_canonical(std::filesystem::absolute(base_dir.empty() ? "." : base_dir, ec), ec);
    }
    tinygltf::TinyGLTF loader;
    loader.SetImageLoader(skip_image, nullptr);
    loader.SetFsCallbacks(tinygltf::FsCallbacks{guarded_exists, tinygltf::ExpandFilePath, guarded_read, refuse_write, &guard});
    tinygltf::Model model;
    std::string err, warn;
    bool ok = false;
    const bool glb = is_glb;
    try {
        ok = glb ? loader.LoadBinaryFromMemory(&model, &err, &warn, bytes, static_cast<unsigned int>(size), base_dir)
                 : loader.LoadASCIIFromString(&model, &err, &warn, reinterpret_cast<const char*>(bytes), static_cast<unsigned int>(size), base_dir);
    } catch (const std::exception& e) {
        return make_error(file, std::string("glTF parser failed: ") + e.what());
    }
    if (!ok) {
        while (!err.empty() && (err.back() == '\n' || err.back() == ' ')) err.pop_back();
        return make_error(file, "not a valid glTF file: " + (err.empty() ? std::string("unknown error") : err));
    }
    return convert(model, file);
}

}  // namespace

Result<GltfCharacter> parse_gltf_character(std::string_view json_text, const std::string& source_name, const std::string& base_dir) {
    return load_from_memory(reinterpret_cast<const unsigned char*>(json_text.data()), json_text.size(), source_name, base_dir);
}

Result<GltfCharacter> load_gltf_character(const std::string& path) {
    Result<std::vector<unsigned char>> bytes = read_binary_file(path);
    if (!bytes.ok()) return bytes.error();
    const std::string base_dir = std::filesystem::path(path).parent_path().string();
    return load_from_memory(bytes.value().data(), bytes.value().size(), path, base_dir);
}

}  // namespace aloha
