// Test helper: builds small glTF 2.0 files in code (one embedded base64 buffer), so each loader
// feature gets a fixture written by the project. Add typed accessors, nodes, meshes, skins and
// materials; dump() gives the .gltf JSON text.
#pragma once

#include <glm/glm.hpp>
#include <nlohmann/json.hpp>

#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

namespace aloha::test {

/// Standard base64 of `in` (for data: URIs).
inline std::string base64(const std::vector<unsigned char>& in) {
    static const char* k = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string out;
    for (size_t i = 0; i < in.size(); i += 3) {
        const uint32_t n = (uint32_t{in[i]} << 16) | (i + 1 < in.size() ? uint32_t{in[i + 1]} << 8 : 0) | (i + 2 < in.size() ? in[i + 2] : 0);
        out += k[(n >> 18) & 63];
        out += k[(n >> 12) & 63];
        out += i + 1 < in.size() ? k[(n >> 6) & 63] : '=';
        out += i + 2 < in.size() ? k[n & 63] : '=';
    }
    return out;
}

/// A glTF document under construction. Indices returned are the glTF array indices.
class GltfBuilder {
public:
    nlohmann::json doc;  ///< edit freely (nodes, meshes, skins, materials...) before dump()

    GltfBuilder() {
        doc["asset"] = {{"version", "2.0"}};
        doc["scene"] = 0;
        doc["scenes"] = nlohmann::json::array({{{"nodes", nlohmann::json::array()}}});
        for (const char* a : {"nodes", "meshes", "skins", "accessors", "bufferViews", "materials"}) doc[a] = nlohmann::json::array();
    }

    /// Accessor over `values` of glTF `type` ("VEC3", ...) and component type (5126 float, 5121
    /// ubyte, 5123 ushort, 5125 uint); `normalized` sets the accessor flag.
    template <class T>
    int accessor(const std::vector<T>& values, const std::string& type, int component, bool normalized = false) {
        while (bin_.size() % 4 != 0) bin_.push_back(0);
        const size_t offset = bin_.size();
        bin_.resize(offset + values.size() * sizeof(T));
        std::memcpy(bin_.data() + offset, values.data(), values.size() * sizeof(T));
        const size_t comps = type == "SCALAR" ? 1 : type == "VEC2" ? 2 : type == "VEC3" ? 3 : type == "VEC4" ? 4 : 16;
        doc["bufferViews"].push_back({{"buffer", 0}, {"byteOffset", offset}, {"byteLength", values.size() * sizeof(T)}});
        nlohmann::json a = {{"bufferView", doc["bufferViews"].size() - 1}, {"componentType", component},
                            {"count", values.size() / comps}, {"type", type}};
        if (normalized) a["normalized"] = true;
        doc["accessors"].push_back(a);
        return static_cast<int>(doc["accessors"].size() - 1);
    }
    /// Float accessors.
    int vec2(const std::vector<glm::vec2>& v) { return accessor(flat(v), "VEC2", 5126); }
    int vec3(const std::vector<glm::vec3>& v) { return accessor(flat(v), "VEC3", 5126); }
    int vec4(const std::vector<glm::vec4>& v) { return accessor(flat(v), "VEC4", 5126); }
    int mat4(const std::vector<glm::mat4>& m) {
        std::vector<float> f;
        for (const glm::mat4& x : m)
            for (int c = 0; c < 4; ++c)
                for (int r = 0; r < 4; ++r) f.push_back(x[c][r]);
        return accessor(f, "MAT4", 5126);
    }
    int scalars(const std::vector<float>& v) { return accessor(v, "SCALAR", 5126); }
    /// JOINTS_n as unsigned shorts (4 per vertex).
    int joints(const std::vector<uint16_t>& v) { return accessor(v, "VEC4", 5123); }
    /// Triangle indices as unsigned shorts.
    int indices(const std::vector<uint16_t>& v) { return accessor(v, "SCALAR", 5123); }

    /// A buffer view over `bytes` (4-byte aligned; `stride` > 0 sets byteStride); returns its index.
    int view(const std::vector<unsigned char>& bytes, size_t stride = 0) {
        while (bin_.size() % 4 != 0) bin_.push_back(0);
        const size_t offset = bin_.size();
        bin_.insert(bin_.end(), bytes.begin(), bytes.end());
        nlohmann::json v = {{"buffer", 0}, {"byteOffset", offset}, {"byteLength", bytes.size()}};
        if (stride > 0) v["byteStride"] = stride;
        doc["bufferViews"].push_back(v);
        return static_cast<int>(doc["bufferViews"].size() - 1);
    }
    /// An accessor over buffer view `view_index` (no bytes added); returns its index.
    int accessor_on(int view_index, size_t count, const std::string& type, int component, bool normalized = false) {
        nlohmann::json a = {{"bufferView", view_index}, {"componentType", component}, {"count", count}, {"type", type}};
        if (normalized) a["normalized"] = true;
        doc["accessors"].push_back(a);
        return static_cast<int>(doc["accessors"].size() - 1);
    }

    /// Appends a node (a JSON object: name, translation, children...) and returns its index.
    int node(const nlohmann::json& n) {
        doc["nodes"].push_back(n);
        return static_cast<int>(doc["nodes"].size() - 1);
    }
    /// Appends a mesh with these primitives.
    int mesh(const nlohmann::json& primitives) {
        doc["meshes"].push_back({{"primitives", primitives}});
        return static_cast<int>(doc["meshes"].size() - 1);
    }
    /// Appends a skin over joint nodes with inverse bind matrices (none when empty).
    int skin(const std::vector<int>& joint_nodes, const std::vector<glm::mat4>& inverse_binds) {
        nlohmann::json s = {{"joints", joint_nodes}};
        if (!inverse_binds.empty()) s["inverseBindMatrices"] = mat4(inverse_binds);
        doc["skins"].push_back(s);
        return static_cast<int>(doc["skins"].size() - 1);
    }
    /// Makes `node` a root of the scene.
    void root(int node) { doc["scenes"][0]["nodes"].push_back(node); }
    /// Embeds `bytes` (e.g. a PNG) as an image in the buffer; returns the image index.
    int image(const std::vector<unsigned char>& bytes, const std::string& mime = "image/png") {
        while (bin_.size() % 4 != 0) bin_.push_back(0);
        const size_t offset = bin_.size();
        bin_.insert(bin_.end(), bytes.begin(), bytes.end());
        doc["bufferViews"].push_back({{"buffer", 0}, {"byteOffset", offset}, {"byteLength", bytes.size()}});
        doc["images"].push_back({{"bufferView", doc["bufferViews"].size() - 1}, {"mimeType", mime}});
        return static_cast<int>(doc["images"].size() - 1);
    }

    /// The JSON text with the buffer embedded.
    std::string dump() {
        nlohmann::json d = doc;
        if (bin_.empty()) bin_.assign(4, 0);  // tinygltf refuses an empty data URI
        d["buffers"] = nlohmann::json::array({{{"byteLength", bin_.size()}, {"uri", "data:application/octet-stream;base64," + base64(bin_)}}});
        for (const char* a : {"skins", "materials"})
            if (d[a].empty()) d.erase(a);
        return d.dump();
    }

private:
    template <class V>
    static std::vector<float> flat(const std::vector<V>& v) {
        std::vector<float> f;
        for (const V& x : v)
            for (int c = 0; c < V::length(); ++c) f.push_back(x[c]);
        return f;
    }
    std::vector<unsigned char> bin_;
};

}  // namespace aloha::test
