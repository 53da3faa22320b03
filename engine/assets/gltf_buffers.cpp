// Buffer preparation of the glTF loader. Before tinygltf: compressed files are rewritten where tinygltf
// refuses what the compression extensions allow. Before any accessor is read: the file's required
// extensions are checked against what the loader reads, buffer views compressed with
// EXT_meshopt_compression (gltfpack -c) are decoded with meshoptimizer into buffers of their own, and
// KHR_draco_mesh_compression primitives are decoded (gltf_draco.cpp), so the accessor reader sees plain data.
#include "engine/assets/gltf_detail.hpp"

#include <meshoptimizer.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cstring>
#include <string_view>

namespace aloha::gltf_detail {

namespace {

constexpr std::string_view kMeshopt = kMeshoptExtension;
constexpr std::string_view kDraco = kDracoExtension;

// What each unsupported extension a file can require does, and what to do about it.
std::string unsupported_hint(const std::string& name) {
    if (name == "KHR_texture_basisu" || name == "EXT_texture_avif")
        return "only PNG, JPEG and WebP images are decoded; export the textures as PNG, JPEG or WebP";
    if (name == "KHR_meshopt_compression")
        return "only its earlier form EXT_meshopt_compression is decoded (the Debian meshoptimizer 0.18 has no newer codec); re-pack with "
               "`gltfpack -c`";
    return "the loader does not read it, and the file says it cannot be drawn without it";
}

// A non-negative integer member `key` of a JSON object value, or -1 when missing or not one.
int64_t int_member(const tinygltf::Value& object, const char* key) { return object.Has(key) ? non_negative_integer(object.Get(key)) : -1; }

std::string string_member(const tinygltf::Value& object, const char* key, const std::string& fallback) {
    if (!object.Has(key)) return fallback;
    const tinygltf::Value& v = object.Get(key);
    return v.IsString() ? v.Get<std::string>() : std::string("(not a string)");
}

// The most bytes meshoptimizer's codecs decode from `length` compressed bytes: the vertex codec spends at least
// 2 header bits on each 16-byte group of a byte column (64:1, what an all-zero buffer reaches; the index codecs
// reach 12:1 and 4:1), plus a margin for the codec's fixed header and tail. It bounds the allocation a
// hostile count and byteStride could ask for.
size_t meshopt_decoded_limit(size_t length) { return 64 * length + 4096; }

// Decodes buffer view `index` (which carries the extension object `ext`) into `out`; `vertex_stride` gets the
// byteStride of mode ATTRIBUTES (vertex data, whose stride the view keeps), 0 for indices. Everything is checked
// before the output is allocated.
Status decode_meshopt_view(const tinygltf::Model& model, size_t index, const tinygltf::Value& ext, const std::string& file,
                           std::vector<unsigned char>* out, size_t* vertex_stride) {
    const std::string where = "bufferViews[" + std::to_string(index) + "].extensions." + std::string(kMeshopt);
    auto fail = [&](const std::string& msg) { return make_error(file, msg, 0, 0, where); };
    if (!ext.IsObject()) return fail("is not an object");
    const int64_t buffer = int_member(ext, "buffer"), offset = ext.Has("byteOffset") ? int_member(ext, "byteOffset") : 0;
    const int64_t length = int_member(ext, "byteLength"), stride = int_member(ext, "byteStride"), count = int_member(ext, "count");
    if (buffer < 0) return fail("'buffer' is missing or not a non-negative integer");
    if (offset < 0) return fail("'byteOffset' is not a non-negative integer");
    if (length < 0) return fail("'byteLength' is missing or not a non-negative integer");
    if (stride < 1) return fail("'byteStride' is missing or not a positive integer");
    if (count < 1) return fail("'count' is missing or not a positive integer");
    if (static_cast<size_t>(count) > kMaxGltfAccessorCount)
        return fail("count " + std::to_string(count) + " exceeds the limit of " + std::to_string(kMaxGltfAccessorCount));
    if (static_cast<size_t>(buffer) >= model.buffers.size())
        return fail("buffer " + std::to_string(buffer) + " is out of range (the file has " + std::to_string(model.buffers.size()) + " buffers)");
    const std::vector<unsigned char>& src = model.buffers[static_cast<size_t>(buffer)].data;
    if (static_cast<size_t>(offset) > src.size() || static_cast<size_t>(length) > src.size() - static_cast<size_t>(offset))
        return fail("byte range " + std::to_string(offset) + "+" + std::to_string(length) + " exceeds buffers[" + std::to_string(buffer) + "] of " +
                    std::to_string(src.size()) + " bytes");
    const std::string mode = string_member(ext, "mode", "(missing)");
    const std::string filter = string_member(ext, "filter", "NONE");
    const auto n = static_cast<size_t>(count), s = static_cast<size_t>(stride);
    const bool attributes = mode == "ATTRIBUTES";
    *vertex_stride = attributes ? s : 0;
    if (attributes) {
        if (s % 4 != 0 || s > 256) return fail("byteStride " + std::to_string(s) + " must be a multiple of 4 up to 256 for mode ATTRIBUTES");
    } else if (mode == "TRIANGLES" || mode == "INDICES") {
        if (s != 2 && s != 4) return fail("byteStride " + std::to_string(s) + " must be 2 or 4 for mode " + mode);
        if (mode == "TRIANGLES" && n % 3 != 0) return fail("count " + std::to_string(n) + " is not a multiple of 3 for mode TRIANGLES");
    } else {
        return fail("mode '" + mode + "' is not ATTRIBUTES, TRIANGLES or INDICES");
    }
    const bool filter_fits = filter == "NONE" || (filter == "OCTAHEDRAL" && attributes && (s == 4 || s == 8)) ||
                             (filter == "QUATERNION" && attributes && s == 8) || (filter == "EXPONENTIAL" && attributes);
    if (filter != "NONE" && filter != "OCTAHEDRAL" && filter != "QUATERNION" && filter != "EXPONENTIAL")
        return fail("filter '" + filter + "' is not NONE, OCTAHEDRAL, QUATERNION or EXPONENTIAL");
    if (!filter_fits)
        return fail("filter " + filter + " needs mode ATTRIBUTES and byteStride " +
                    (filter == "OCTAHEDRAL" ? "4 or 8" : filter == "QUATERNION" ? "8" : "a multiple of 4"));
    const tinygltf::BufferView& view = model.bufferViews[index];
    if (view.byteLength != n * s)
        return fail("count x byteStride = " + std::to_string(n * s) + " bytes, but the buffer view's byteLength is " + std::to_string(view.byteLength));
    if (n * s > meshopt_decoded_limit(static_cast<size_t>(length)))
        return fail(std::to_string(n * s) + " bytes cannot decode from " + std::to_string(length) + " compressed bytes (at most " +
                    std::to_string(meshopt_decoded_limit(static_cast<size_t>(length))) + ")");
    const unsigned char* data = src.data() + offset;
    out->assign(n * s, 0);
    const int rc = attributes           ? meshopt_decodeVertexBuffer(out->data(), n, s, data, static_cast<size_t>(length))
                   : mode == "TRIANGLES" ? meshopt_decodeIndexBuffer(out->data(), n, s, data, static_cast<size_t>(length))
                                         : meshopt_decodeIndexSequence(out->data(), n, s, data, static_cast<size_t>(length));
    if (rc != 0) return fail("the compressed data does not decode as mode " + mode + " (meshoptimizer error " + std::to_string(rc) + ")");
    if (filter == "OCTAHEDRAL") meshopt_decodeFilterOct(out->data(), n, s);
    if (filter == "QUATERNION") meshopt_decodeFilterQuat(out->data(), n, s);
    if (filter == "EXPONENTIAL") meshopt_decodeFilterExp(out->data(), n, s);
    return {};
}

}  // namespace

int64_t non_negative_integer(const tinygltf::Value& v) {
    if (!v.IsNumber()) return -1;
    const double d = v.GetNumberAsDouble();
    if (!(d >= 0.0) || d > 9.0e15 || d != static_cast<double>(static_cast<int64_t>(d))) return -1;
    return static_cast<int64_t>(d);
}

std::optional<std::vector<unsigned char>> rewritten_for_tinygltf(const unsigned char* bytes, size_t size, bool glb) {
    size_t begin = 0, length = size;
    if (glb) {
        if (size < 20) return std::nullopt;
        length = glb_u32(bytes + 12);
        begin = 20;
        // tinygltf reports the broken chunk or header; a rewrite would write a consistent total over it.
        if (length > size - 20 || glb_u32(bytes + 8) != size) return std::nullopt;
    }
    const std::string_view text(reinterpret_cast<const char*>(bytes) + begin, length);
    const bool meshopt = text.find(kMeshopt) != std::string_view::npos && text.find("fallback") != std::string_view::npos;
    const bool draco = text.find(kDraco) != std::string_view::npos;
    if (!meshopt && !draco) return std::nullopt;
    nlohmann::json doc = nlohmann::json::parse(text, nullptr, false);
    if (doc.is_discarded() || !doc.is_object()) return std::nullopt;
    bool changed = false;
    // Draco: the indices accessor of a compressed primitive has no bufferView (the spec's way), which
    // tinygltf refuses; it gets the compressed view (or, when that is missing or out of range, view 0, so
    // that decode_draco_primitives() reports the extension's problem), replaced by the decoded indices.
    const size_t views = doc.contains("bufferViews") && doc["bufferViews"].is_array() ? doc["bufferViews"].size() : 0;
    if (draco && views > 0 && doc.contains("meshes") && doc["meshes"].is_array() && doc.contains("accessors") && doc["accessors"].is_array())
        for (nlohmann::json& mesh : doc["meshes"]) {
            if (!mesh.is_object() || !mesh.contains("primitives") || !mesh["primitives"].is_array()) continue;
            for (nlohmann::json& prim : mesh["primitives"]) {
                if (!prim.is_object() || !prim.contains("indices") || !prim["indices"].is_number_unsigned() || !prim.contains("extensions") ||
                    !prim["extensions"].is_object())
                    continue;
                const auto ext = prim["extensions"].find(std::string(kDraco));
                if (ext == prim["extensions"].end() || !ext->is_object()) continue;
                const auto index = prim["indices"].get<size_t>();
                if (index >= doc["accessors"].size() || !doc["accessors"][index].is_object() || doc["accessors"][index].contains("bufferView")) continue;
                const bool usable = ext->contains("bufferView") && (*ext)["bufferView"].is_number_unsigned() && (*ext)["bufferView"].get<size_t>() < views;
                doc["accessors"][index]["bufferView"] = usable ? (*ext)["bufferView"].get<size_t>() : size_t{0};
                changed = true;
            }
        }
    nlohmann::json no_buffers = nlohmann::json::array();
    nlohmann::json& buffers = meshopt && doc.contains("buffers") && doc["buffers"].is_array() ? doc["buffers"] : no_buffers;
    for (nlohmann::json& buffer : buffers) {
        if (!buffer.is_object() || buffer.contains("uri") || !buffer.contains("extensions") || !buffer["extensions"].is_object()) continue;
        const auto ext = buffer["extensions"].find(std::string(kMeshopt));
        if (ext == buffer["extensions"].end() || !ext->is_object() || ext->value("fallback", false) != true) continue;
        buffer["uri"] = "data:application/octet-stream;base64,AA==";  // one zero byte
        buffer["byteLength"] = 1;
        changed = true;
    }
    if (!changed) return std::nullopt;
    std::string json_text = doc.dump();
    if (!glb) return std::vector<unsigned char>(json_text.begin(), json_text.end());
    while (json_text.size() % 4 != 0) json_text.push_back(' ');
    const size_t rest = size - 20 - length;  // the BIN chunk and anything after it, copied as it is
    const size_t total = 20 + json_text.size() + rest;
    if (total > 0xFFFFFFFFu) return std::nullopt;
    std::vector<unsigned char> out(total);
    std::memcpy(out.data(), bytes, 12);
    auto put32 = [&](size_t at, size_t v) {
        for (int k = 0; k < 4; ++k) out[at + static_cast<size_t>(k)] = static_cast<unsigned char>(v >> (8 * k));
    };
    put32(8, total);
    put32(12, json_text.size());
    std::memcpy(out.data() + 16, bytes + 16, 4);  // chunk type "JSON"
    std::memcpy(out.data() + 20, json_text.data(), json_text.size());
    if (rest > 0) std::memcpy(out.data() + 20 + json_text.size(), bytes + 20 + length, rest);
    return out;
}

std::vector<std::string> supported_required_extensions() {
    return {"KHR_mesh_quantization", std::string(kMeshopt), "KHR_texture_transform", std::string(kDraco), std::string(kWebpExtension),
            "KHR_materials_unlit", "KHR_materials_emissive_strength"};
}

Status prepare_buffers(tinygltf::Model* model, const std::string& file, std::vector<std::string>* notes) {
    const std::vector<std::string> supported = supported_required_extensions();
    for (const std::string& name : model->extensionsRequired)
        if (std::find(supported.begin(), supported.end(), name) == supported.end())
            return make_error(file, "the file requires extension " + name + ": " + unsupported_hint(name), 0, 0, "extensionsRequired");
    const size_t views = model->bufferViews.size();
    size_t decoded_views = 0;
    for (size_t i = 0; i < views; ++i) {
        const auto it = model->bufferViews[i].extensions.find(std::string(kMeshopt));
        if (it == model->bufferViews[i].extensions.end()) continue;
        std::vector<unsigned char> decoded;
        size_t vertex_stride = 0;
        if (Status s = decode_meshopt_view(*model, i, it->second, file, &decoded, &vertex_stride); !s.ok()) return s;
        tinygltf::BufferView& view = model->bufferViews[i];
        tinygltf::Buffer buffer;
        buffer.name = "decoded bufferViews[" + std::to_string(i) + "]";
        buffer.data = std::move(decoded);
        model->buffers.push_back(std::move(buffer));
        view.buffer = static_cast<int>(model->buffers.size() - 1);
        view.byteOffset = 0;
        // Vertex data keeps the extension's stride (the spec makes the view's equal to it); index data is tightly packed.
        if (vertex_stride > 0 && view.byteStride == 0) view.byteStride = vertex_stride;
        view.extensions.erase(std::string(kMeshopt));
        ++decoded_views;
    }
    if (decoded_views > 0)
        notes->push_back(std::string(kMeshopt) + ": " + std::to_string(decoded_views) + " buffer view" + (decoded_views == 1 ? "" : "s") +
                         " decoded (meshoptimizer)");
    size_t primitives = 0;
    if (Status s = decode_draco_primitives(model, file, &primitives); !s.ok()) return s;
    if (primitives > 0)
        notes->push_back(std::string(kDraco) + ": " + std::to_string(primitives) + " primitive" + (primitives == 1 ? "" : "s") + " decoded (Draco)");
    const auto& used = model->extensionsUsed;
    if (std::find(used.begin(), used.end(), "KHR_mesh_quantization") != used.end())
        notes->push_back("KHR_mesh_quantization: integer vertex data read as its accessors say (normalised or not)");
    return {};
}

}  // namespace aloha::gltf_detail
