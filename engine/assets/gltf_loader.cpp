// glTF character loader: runs tinygltf, then checks and converts the skins, meshes, materials and clips.
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

namespace aloha {

namespace {

using namespace gltf_detail;

Result<GltfCharacter> convert(const tinygltf::Model& model, const std::string& file, const ImageDecodeLog& images) {
    Result<std::vector<int>> parents_r = node_parents(model, file);
    if (!parents_r.ok()) return parents_r.error();
    const std::vector<int>& parents = parents_r.value();
    GltfCharacter out;
    Result<SkinSet> skins = read_skins(model, parents, file, &out);
    if (!skins.ok()) return skins.error();
    Result<Skeleton> skeleton = build_skeleton(out.skeleton, file);
    if (!skeleton.ok()) return skeleton.error();
    const std::vector<int> runtime_of_raw = runtime_index_of_raw(skeleton.value());
    if (Status s = read_declared_humanoid(model, skins.value(), file, &out); !s.ok()) return s.error();

    for (const auto& [index, reason] : images.failures)
        out.notes.push_back("images[" + std::to_string(index) + "]: " + reason + "; materials using it are drawn untextured");
    std::vector<MaterialUv> texcoord;
    if (Status s = read_materials(model, file, &out, &texcoord); !s.ok()) return s.error();
    if (Status s = attach_meshes(model, parents, skins.value(), runtime_of_raw, texcoord, file, &out); !s.ok()) return s.error();

    size_t morph_channels = 0;
    for (size_t a = 0; a < model.animations.size(); ++a) {
        Result<RawAnimation> clip = read_clip(model, static_cast<int>(a), skins.value().bindings, file, &out.notes, &morph_channels);
        if (!clip.ok()) return clip.error();
        out.clips.push_back(remap_to_runtime(clip.value(), skeleton.value()));
        out.clip_names.push_back(out.clips.back().name);
    }
    if (morph_channels > 0)
        out.notes.push_back(std::to_string(morph_channels) + " morph target weight channel" + (morph_channels == 1 ? "" : "s") +
                            " skipped: morph weights are not animated");
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

// A GLB's BIN chunk must fit the file with its 8-byte header: tinygltf 2.8 checks its length without that header
// and reads up to 8 bytes past the end of the data (found by fuzz_gltf). Other layout errors are left to tinygltf.
Status check_glb_bin_chunk(const unsigned char* bytes, size_t size, const std::string& file) {
    if (size < 20) return {};
    const uint64_t declared = glb_u32(bytes + 8), json_end = 20ull + glb_u32(bytes + 12);
    const uint64_t end = std::min<uint64_t>(declared, size);
    if (json_end + 8 > end) return {};  // no BIN chunk (or a broken JSON chunk, which tinygltf reports)
    const uint64_t bin = glb_u32(bytes + json_end);
    if (json_end + 8 + bin > end)
        return make_error(file, "not a valid glTF file: the BIN chunk says " + std::to_string(bin) + " bytes, but " +
                                    std::to_string(end - json_end - 8) + " follow its header");
    return {};
}

// Runs tinygltf on `bytes` (GLB when it starts with "glTF", JSON otherwise) and converts.
Result<GltfCharacter> load_from_memory(const unsigned char* bytes, size_t size, const std::string& file, const std::string& base_dir) {
    if (size > std::numeric_limits<unsigned int>::max()) return make_error(file, "file is too large for tinygltf");
    const bool is_glb = size >= 4 && bytes[0] == 'g' && bytes[1] == 'l' && bytes[2] == 'T' && bytes[3] == 'F';
    if (is_glb)
        if (Status s = check_glb_bin_chunk(bytes, size, file); !s.ok()) return s.error();
    {
        // tinygltf converts JSON recursively: refuse hostile nesting before it sees the text.
        size_t begin = 0, length = size;
        if (is_glb) {
            begin = 20;
            length = size >= 20 ? glb_u32(bytes + 12) : 0;
            length = std::min(length, size >= 20 ? size - 20 : 0);
        }
        if (Status deep = check_json_depth(std::string_view(reinterpret_cast<const char*>(bytes) + begin, length), file); !deep.ok())
            return deep.error();
    }
    const std::optional<std::vector<unsigned char>> rewritten = rewritten_for_tinygltf(bytes, size, is_glb);
    if (rewritten) {
        bytes = rewritten->data();
        size = rewritten->size();
    }
    FolderGuard guard;
    {
        std::error_code ec;
        guard.folder = std::filesystem::weakly_canonical(std::filesystem::absolute(base_dir.empty() ? "." : base_dir, ec), ec);
    }
    tinygltf::TinyGLTF loader;
    ImageDecodeLog images;
    loader.SetImageLoader(decode_image, &images);
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
    decode_buffer_view_images(&model, &images);
    std::vector<std::string> decoded;
    if (Status prepared = prepare_buffers(&model, file, &decoded); !prepared.ok()) return prepared.error();
    if (model.skins.empty()) {
        Result<std::vector<int>> parents = node_parents(model, file);
        if (!parents.ok()) return parents.error();
        if (Status s = add_node_skin(&model, parents.value(), file, &decoded); !s.ok()) return s.error();
    }
    Result<GltfCharacter> character = convert(model, file, images);
    if (character.ok()) character.value().notes.insert(character.value().notes.begin(), decoded.begin(), decoded.end());
    return character;
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
