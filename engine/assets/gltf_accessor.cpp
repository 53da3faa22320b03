// Validated accessor reads for the glTF loader: every index, range, type and count is checked
// against the file before a byte is read; accessors without a buffer view read as zeros, and sparse
// accessors get their substituted values.
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

// A checked window into a buffer: element k component c is at base + k*stride + c*comp_size.
struct View {
    const unsigned char* base = nullptr;
    size_t stride = 0;
    size_t count = 0;
    size_t comps = 0;
    int comp_type = 0;
    size_t comp_size = 0;
};

// A checked window of `count` elements of `comps` components of `comp_type` in buffer view `bv_index`,
// from `byte_offset`; `strided` lets the view's byteStride apply (sparse data is always tightly packed).
Result<View> window(const tinygltf::Model& model, int bv_index, size_t byte_offset, size_t count, size_t comps, int comp_type, bool strided,
                    const std::string& file, const std::string& where) {
    if (bv_index < 0 || static_cast<size_t>(bv_index) >= model.bufferViews.size())
        return make_error(file, "bufferView " + std::to_string(bv_index) + " is out of range (the file has " + std::to_string(model.bufferViews.size()) +
                                    " bufferViews)", 0, 0, where);
    const std::string bv_where = "bufferViews[" + std::to_string(bv_index) + "]";
    const tinygltf::BufferView& bv = model.bufferViews[static_cast<size_t>(bv_index)];
    auto fail_bv = [&](const std::string& msg) { return make_error(file, msg + " (used by " + where + ")", 0, 0, bv_where); };
    if (bv.buffer < 0 || static_cast<size_t>(bv.buffer) >= model.buffers.size())
        return fail_bv("buffer " + std::to_string(bv.buffer) + " is out of range (the file has " + std::to_string(model.buffers.size()) + " buffers)");
    const tinygltf::Buffer& buf = model.buffers[static_cast<size_t>(bv.buffer)];
    if (buf.data.empty())
        return make_error(file, "buffer has no data (missing or unreadable uri '" + buf.uri + "')", 0, 0, "buffers[" + std::to_string(bv.buffer) + "]");
    if (bv.byteOffset > buf.data.size() || bv.byteLength > buf.data.size() - bv.byteOffset)
        return fail_bv("byte range " + std::to_string(bv.byteOffset) + "+" + std::to_string(bv.byteLength) + " exceeds buffers[" + std::to_string(bv.buffer) +
                       "] of " + std::to_string(buf.data.size()) + " bytes");
    View v;
    v.comps = comps;
    v.comp_size = static_cast<size_t>(tinygltf::GetComponentSizeInBytes(static_cast<uint32_t>(comp_type)));
    const size_t elem = v.comps * v.comp_size;
    const size_t stride = strided ? bv.byteStride : 0;
    if (stride != 0 && (stride < elem || stride > 252))
        return fail_bv("byteStride " + std::to_string(stride) + " is invalid for " + std::to_string(elem) + "-byte elements");
    v.stride = stride != 0 ? stride : elem;
    if (byte_offset > bv.byteLength || (count - 1) * v.stride + elem > bv.byteLength - byte_offset)
        return make_error(file, "needs " + std::to_string(byte_offset + (count - 1) * v.stride + elem) + " bytes of " + bv_where + ", which has " +
                                    std::to_string(bv.byteLength), 0, 0, where);
    v.base = buf.data.data() + bv.byteOffset + byte_offset;
    v.count = count;
    v.comp_type = comp_type;
    return v;
}

// The accessor's checked header, its dense window (none when it has no bufferView: all zeros) and its
// sparse substitutions (indices and values windows, indices checked increasing and in range).
struct AccessorData {
    View dense;
    bool has_dense = false;
    size_t count = 0, comps = 0;
    bool normalized = false;
    std::vector<uint32_t> sparse_indices;
    View sparse_values;
};

uint32_t to_uint(const unsigned char* p, int comp_type);

Result<AccessorData> accessor_data(const tinygltf::Model& model, int index, int type, const std::vector<int>& allowed,
                                   const std::string& file, const std::string& usage) {
    if (index < 0 || static_cast<size_t>(index) >= model.accessors.size())
        return make_error(file, "refers to accessor " + std::to_string(index) + ", but the file has " +
                                    std::to_string(model.accessors.size()) + " accessors", 0, 0, usage);
    const std::string where = "accessors[" + std::to_string(index) + "]";
    const tinygltf::Accessor& a = model.accessors[static_cast<size_t>(index)];
    auto fail = [&](const std::string& msg, const std::string& at) { return make_error(file, msg + " (used by " + usage + ")", 0, 0, at); };
    if (a.type != type) return fail("type is " + type_name(a.type) + ", expected " + type_name(type), where);
    if (std::find(allowed.begin(), allowed.end(), a.componentType) == allowed.end()) {
        std::string list;
        for (int c : allowed) list += (list.empty() ? "" : " or ") + component_name(c);
        return fail("component type is " + component_name(a.componentType) + ", expected " + list, where);
    }
    if (a.count == 0) return fail("count is 0", where);
    if (a.count > kMaxGltfAccessorCount)
        return fail("count " + std::to_string(a.count) + " exceeds the limit of " + std::to_string(kMaxGltfAccessorCount), where);
    AccessorData d;
    d.count = a.count;
    d.comps = static_cast<size_t>(tinygltf::GetNumComponentsInType(static_cast<uint32_t>(a.type)));
    d.normalized = a.normalized;
    if (a.bufferView >= 0) {
        Result<View> dense = window(model, a.bufferView, a.byteOffset, a.count, d.comps, a.componentType, true, file, where);
        if (!dense.ok()) return dense.error();
        d.dense = dense.value();
        d.has_dense = true;
    } else if (a.byteOffset != 0) {
        return fail("has a byteOffset but no bufferView", where);
    } else {
        // Zeros come from no bytes of the file: bound what a small file can make the loader allocate. A real one
        // (morph deltas, as many as the positions stored in a buffer) needs under 4 bytes a stored byte.
        size_t stored = 0;
        for (const tinygltf::Buffer& b : model.buffers) stored += b.data.size();
        const size_t bytes = a.count * d.comps * sizeof(float), limit = 16 * stored + (size_t{1} << 20);
        if (bytes > limit)
            return fail("has no bufferView and " + std::to_string(a.count) + " elements: " + std::to_string(bytes) +
                            " bytes of zeros, more than the file's buffers can account for (at most " + std::to_string(limit) + ")",
                        where);
    }
    if (!a.sparse.isSparse) return d;
    const std::string sw = where + ".sparse";
    const auto sparse_count = static_cast<size_t>(std::max(a.sparse.count, 0));
    if (a.sparse.count < 1 || sparse_count > a.count)
        return fail("count " + std::to_string(a.sparse.count) + " is not between 1 and the accessor's count " + std::to_string(a.count), sw);
    const int ic = a.sparse.indices.componentType;
    if (ic != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE && ic != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT && ic != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT)
        return fail("indices component type is " + component_name(ic) + ", expected UNSIGNED_BYTE, UNSIGNED_SHORT or UNSIGNED_INT", sw + ".indices");
    Result<View> iv = window(model, a.sparse.indices.bufferView, static_cast<size_t>(std::max(a.sparse.indices.byteOffset, 0)), sparse_count, 1, ic, false,
                             file, sw + ".indices");
    if (!iv.ok()) return iv.error();
    d.sparse_indices.resize(sparse_count);
    for (size_t k = 0; k < sparse_count; ++k) {
        const uint32_t i = to_uint(iv.value().base + k * iv.value().stride, ic);
        if (i >= a.count) return fail("index " + std::to_string(k) + " is " + std::to_string(i) + ", past the accessor's count " + std::to_string(a.count), sw + ".indices");
        if (k > 0 && i <= d.sparse_indices[k - 1])
            return fail("index " + std::to_string(k) + " is " + std::to_string(i) + ", not greater than the one before (indices must increase)", sw + ".indices");
        d.sparse_indices[k] = i;
    }
    Result<View> vv = window(model, a.sparse.values.bufferView, static_cast<size_t>(std::max(a.sparse.values.byteOffset, 0)), sparse_count, d.comps,
                             a.componentType, false, file, sw + ".values");
    if (!vv.ok()) return vv.error();
    d.sparse_values = vv.value();
    return d;
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

// Every element of `d` through `convert(bytes, component type)`: the dense data (or zeros), then the sparse values.
template <class T, class Convert>
std::vector<T> elements(const AccessorData& d, int comp_type, Convert convert) {
    std::vector<T> out(d.count * d.comps, T{});
    if (d.has_dense)
        for (size_t k = 0; k < d.count; ++k)
            for (size_t c = 0; c < d.comps; ++c) out[k * d.comps + c] = convert(d.dense.base + k * d.dense.stride + c * d.dense.comp_size, comp_type);
    for (size_t k = 0; k < d.sparse_indices.size(); ++k)
        for (size_t c = 0; c < d.comps; ++c)
            out[d.sparse_indices[k] * d.comps + c] = convert(d.sparse_values.base + k * d.sparse_values.stride + c * d.sparse_values.comp_size, comp_type);
    return out;
}

}  // namespace

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

Result<std::vector<float>> read_floats(const tinygltf::Model& model, int index, int type, const std::vector<int>& allowed,
                                       const std::string& file, const std::string& usage, bool force_normalize) {
    Result<AccessorData> data = accessor_data(model, index, type, allowed, file, usage);
    if (!data.ok()) return data.error();
    const bool normalize = data.value().normalized || force_normalize;
    const int comp_type = model.accessors[static_cast<size_t>(index)].componentType;
    return elements<float>(data.value(), comp_type, [normalize](const unsigned char* p, int c) { return to_float(p, c, normalize); });
}

Result<std::vector<uint32_t>> read_uints(const tinygltf::Model& model, int index, int type, const std::vector<int>& allowed,
                                         const std::string& file, const std::string& usage) {
    Result<AccessorData> data = accessor_data(model, index, type, allowed, file, usage);
    if (!data.ok()) return data.error();
    const int comp_type = model.accessors[static_cast<size_t>(index)].componentType;
    return elements<uint32_t>(data.value(), comp_type, [](const unsigned char* p, int c) { return to_uint(p, c); });
}

}  // namespace aloha::gltf_detail
