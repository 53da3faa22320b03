// Validated accessor reads for the glTF loader: every index, range, type and count is checked
// against the file before a byte is read.
#include "engine/assets/gltf_detail.hpp"

#include <algorithm>
#include <cstring>

namespace aloha::gltf_detail {

namespace {

std::string type_name(int type) {
    switch (type) {
        case TINYGLTF_TYPE_SCALAR: return "SCALAR";
        case TINYGLTF_TYPE_VEC2: return "VEC2";
        case TINYGLTF_TYPE_VEC3: return "VEC3";
        case TINYGLTF_TYPE_VEC4: return "VEC4";
        case TINYGLTF_TYPE_MAT2: return "MAT2";
        case TINYGLTF_TYPE_MAT3: return "MAT3";
        case TINYGLTF_TYPE_MAT4: return "MAT4";
        default: return "unknown type " + std::to_string(type);
    }
}

std::string component_name(int c) {
    switch (c) {
        case TINYGLTF_COMPONENT_TYPE_BYTE: return "BYTE";
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return "UNSIGNED_BYTE";
        case TINYGLTF_COMPONENT_TYPE_SHORT: return "SHORT";
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: return "UNSIGNED_SHORT";
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: return "UNSIGNED_INT";
        case TINYGLTF_COMPONENT_TYPE_FLOAT: return "FLOAT";
        default: return "unknown component type " + std::to_string(c);
    }
}

// A checked window into a buffer: element k component c is at base + k*stride + c*comp_size.
struct View {
    const unsigned char* base = nullptr;
    size_t stride = 0;
    size_t count = 0;
    size_t comps = 0;
    int comp_type = 0;
    size_t comp_size = 0;
    bool normalized = false;
};

Result<View> accessor_view(const tinygltf::Model& model, int index, int type, const std::vector<int>& allowed,
                           const std::string& file, const std::string& usage) {
    if (index < 0 || static_cast<size_t>(index) >= model.accessors.size())
        return make_error(file, "refers to accessor " + std::to_string(index) + ", but the file has " +
                                    std::to_string(model.accessors.size()) + " accessors", 0, 0, usage);
    const std::string where = "accessors[" + std::to_string(index) + "]";
    const tinygltf::Accessor& a = model.accessors[static_cast<size_t>(index)];
    auto fail = [&](const std::string& msg) { return make_error(file, msg + " (used by " + usage + ")", 0, 0, where); };
    if (a.sparse.isSparse) return fail("sparse accessors are not supported");
    if (a.type != type) return fail("type is " + type_name(a.type) + ", expected " + type_name(type));
    if (std::find(allowed.begin(), allowed.end(), a.componentType) == allowed.end()) {
        std::string list;
        for (int c : allowed) list += (list.empty() ? "" : " or ") + component_name(c);
        return fail("component type is " + component_name(a.componentType) + ", expected " + list);
    }
    if (a.count == 0) return fail("count is 0");
    if (a.count > kMaxGltfAccessorCount)
        return fail("count " + std::to_string(a.count) + " exceeds the limit of " + std::to_string(kMaxGltfAccessorCount));
    if (a.bufferView < 0) return fail("has no bufferView (implicit all-zero accessors are not supported)");
    if (static_cast<size_t>(a.bufferView) >= model.bufferViews.size())
        return fail("bufferView " + std::to_string(a.bufferView) + " is out of range (the file has " +
                    std::to_string(model.bufferViews.size()) + " bufferViews)");
    const std::string bv_where = "bufferViews[" + std::to_string(a.bufferView) + "]";
    const tinygltf::BufferView& bv = model.bufferViews[static_cast<size_t>(a.bufferView)];
    auto fail_bv = [&](const std::string& msg) { return make_error(file, msg + " (used by " + where + ")", 0, 0, bv_where); };
    if (bv.buffer < 0 || static_cast<size_t>(bv.buffer) >= model.buffers.size())
        return fail_bv("buffer " + std::to_string(bv.buffer) + " is out of range (the file has " +
                       std::to_string(model.buffers.size()) + " buffers)");
    const tinygltf::Buffer& buf = model.buffers[static_cast<size_t>(bv.buffer)];
    if (buf.data.empty())
        return make_error(file, "buffer has no data (missing or unreadable uri '" + buf.uri + "')", 0, 0,
                          "buffers[" + std::to_string(bv.buffer) + "]");
    if (bv.byteOffset > buf.data.size() || bv.byteLength > buf.data.size() - bv.byteOffset)
        return fail_bv("byte range " + std::to_string(bv.byteOffset) + "+" + std::to_string(bv.byteLength) +
                       " exceeds buffers[" + std::to_string(bv.buffer) + "] of " + std::to_string(buf.data.size()) + " bytes");
    View v;
    v.comps = static_cast<size_t>(tinygltf::GetNumComponentsInType(static_cast<uint32_t>(a.type)));
    v.comp_size = static_cast<size_t>(tinygltf::GetComponentSizeInBytes(static_cast<uint32_t>(a.componentType)));
    const size_t elem = v.comps * v.comp_size;
    if (bv.byteStride != 0 && (bv.byteStride < elem || bv.byteStride > 252))
        return fail_bv("byteStride " + std::to_string(bv.byteStride) + " is invalid for " + std::to_string(elem) + "-byte elements");
    v.stride = bv.byteStride != 0 ? bv.byteStride : elem;
    if (a.byteOffset > bv.byteLength || (a.count - 1) * v.stride + elem > bv.byteLength - a.byteOffset)
        return fail("needs " + std::to_string(a.byteOffset + (a.count - 1) * v.stride + elem) + " bytes of " + bv_where +
                    ", which has " + std::to_string(bv.byteLength));
    v.base = buf.data.data() + bv.byteOffset + a.byteOffset;
    v.count = a.count;
    v.comp_type = a.componentType;
    v.normalized = a.normalized;
    return v;
}

template <class T>
T load(const unsigned char* p) {
    T value;
    std::memcpy(&value, p, sizeof(T));
    return value;
}

float to_float(const unsigned char* p, int comp_type, bool normalize) {
    switch (comp_type) {
        case TINYGLTF_COMPONENT_TYPE_BYTE: {
            const float v = load<int8_t>(p);
            return normalize ? std::max(v / 127.0f, -1.0f) : v;
        }
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return normalize ? load<uint8_t>(p) / 255.0f : load<uint8_t>(p);
        case TINYGLTF_COMPONENT_TYPE_SHORT: {
            const float v = load<int16_t>(p);
            return normalize ? std::max(v / 32767.0f, -1.0f) : v;
        }
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: return normalize ? load<uint16_t>(p) / 65535.0f : load<uint16_t>(p);
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: return static_cast<float>(load<uint32_t>(p));
        default: return load<float>(p);
    }
}

uint32_t to_uint(const unsigned char* p, int comp_type) {
    switch (comp_type) {
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return load<uint8_t>(p);
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: return load<uint16_t>(p);
        default: return load<uint32_t>(p);
    }
}

}  // namespace

Result<std::vector<float>> read_floats(const tinygltf::Model& model, int index, int type, const std::vector<int>& allowed,
                                       const std::string& file, const std::string& usage, bool force_normalize) {
    Result<View> view = accessor_view(model, index, type, allowed, file, usage);
    if (!view.ok()) return view.error();
    const View& v = view.value();
    const bool normalize = v.normalized || force_normalize;
    std::vector<float> out(v.count * v.comps);
    for (size_t k = 0; k < v.count; ++k)
        for (size_t c = 0; c < v.comps; ++c)
            out[k * v.comps + c] = to_float(v.base + k * v.stride + c * v.comp_size, v.comp_type, normalize);
    return out;
}

Result<std::vector<uint32_t>> read_uints(const tinygltf::Model& model, int index, int type, const std::vector<int>& allowed,
                                         const std::string& file, const std::string& usage) {
    Result<View> view = accessor_view(model, index, type, allowed, file, usage);
    if (!view.ok()) return view.error();
    const View& v = view.value();
    std::vector<uint32_t> out(v.count * v.comps);
    for (size_t k = 0; k < v.count; ++k)
        for (size_t c = 0; c < v.comps; ++c) out[k * v.comps + c] = to_uint(v.base + k * v.stride + c * v.comp_size, v.comp_type);
    return out;
}

}  // namespace aloha::gltf_detail
