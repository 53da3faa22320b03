// The one source that includes Draco (see draco_mesh.hpp): decodes a Draco triangle mesh into plain arrays.
#include "engine/assets/draco_mesh.hpp"

#include <draco/compression/decode.h>

#include <cstring>
#include <exception>
#include <limits>
#include <memory>

namespace aloha {

namespace {

// glTF componentType and the integer range of Draco data type `dt` (0 and 0 when glTF has no such type).
std::pair<int, uint64_t> gltf_type(draco::DataType dt) {
    switch (dt) {
        case draco::DT_INT8: return {5120, 127};
        case draco::DT_UINT8: return {5121, 255};
        case draco::DT_INT16: return {5122, 32767};
        case draco::DT_UINT16: return {5123, 65535};
        case draco::DT_UINT32: return {5125, 0xFFFFFFFFu};
        case draco::DT_FLOAT32: return {5126, 0};
        default: return {0, 0};
    }
}

// Value `avi` of `att` as unnormalised doubles: the stored numbers themselves for glTF's types, Draco's
// conversion for the others.
bool stored_values(const draco::PointAttribute& att, draco::AttributeValueIndex avi, int comps, double* out) {
    if (gltf_type(att.data_type()).first == 0) return att.ConvertValue<double>(avi, static_cast<int8_t>(comps), out);
    unsigned char raw[4 * 4] = {};
    const size_t size = static_cast<size_t>(draco::DataTypeLength(att.data_type()));
    if (size == 0 || size > 4 || comps > 4) return false;
    att.GetValue(avi, raw);
    for (int c = 0; c < comps; ++c) {
        const unsigned char* p = raw + static_cast<size_t>(c) * size;
        switch (att.data_type()) {
            case draco::DT_INT8: out[c] = static_cast<int8_t>(*p); break;
            case draco::DT_UINT8: out[c] = *p; break;
            case draco::DT_INT16: { int16_t v; std::memcpy(&v, p, 2); out[c] = v; break; }
            case draco::DT_UINT16: { uint16_t v; std::memcpy(&v, p, 2); out[c] = v; break; }
            case draco::DT_UINT32: { uint32_t v; std::memcpy(&v, p, 4); out[c] = v; break; }
            default: { float v; std::memcpy(&v, p, 4); out[c] = v; break; }  // DT_FLOAT32
        }
    }
    return true;
}

std::string decode(const unsigned char* data, size_t size, size_t max_values, DracoMesh* out) {
    draco::DecoderBuffer in;
    in.Init(reinterpret_cast<const char*>(data), size);
    const auto type = draco::Decoder::GetEncodedGeometryType(&in);
    if (!type.ok()) return "not Draco data (" + type.status().error_msg_string() + ")";
    if (type.value() != draco::TRIANGULAR_MESH) return "a point cloud, not a triangle mesh";
    draco::Decoder decoder;
    auto decoded = decoder.DecodeMeshFromBuffer(&in);
    if (!decoded.ok()) return "does not decode (Draco: " + decoded.status().error_msg_string() + ")";
    const std::unique_ptr<draco::Mesh> mesh = std::move(decoded).value();
    const size_t points = mesh->num_points(), faces = mesh->num_faces();
    if (points == 0 || points > max_values || faces == 0 || faces > max_values / 3)
        return "the decoded mesh has " + std::to_string(points) + " points and " + std::to_string(faces) +
               " triangles (each must be between 1 and the limit of " + std::to_string(max_values) + " values)";
    out->points = points;
    out->indices.resize(3 * faces);
    for (uint32_t f = 0; f < faces; ++f)
        for (size_t k = 0; k < 3; ++k) {
            const uint32_t v = mesh->face(draco::FaceIndex(f))[k].value();
            if (v >= points) return "triangle " + std::to_string(f) + " uses point " + std::to_string(v) + " of " + std::to_string(points);
            out->indices[3 * f + k] = v;
        }
    for (int32_t i = 0; i < mesh->num_attributes(); ++i) {
        const draco::PointAttribute& att = *mesh->attribute(i);
        DracoAttribute a;
        a.unique_id = att.unique_id();
        a.components = att.num_components();
        const auto [gltf, max] = gltf_type(att.data_type());
        a.gltf_component = gltf;
        a.type_max = max;
        a.normalized = att.normalized();
        if (a.components < 1 || a.components > 4)
            return "attribute " + std::to_string(a.unique_id) + " has " + std::to_string(a.components) + " components (glTF attributes have 1 to 4)";
        if (!att.is_mapping_identity() && att.indices_map_size() < points)
            return "attribute " + std::to_string(a.unique_id) + " maps " + std::to_string(att.indices_map_size()) + " of the " + std::to_string(points) + " points";
        a.values.resize(points * static_cast<size_t>(a.components));
        for (size_t p = 0; p < points; ++p) {
            const draco::AttributeValueIndex avi = att.mapped_index(draco::PointIndex(static_cast<uint32_t>(p)));
            if (avi.value() >= att.size())
                return "point " + std::to_string(p) + " refers to value " + std::to_string(avi.value()) + " of attribute " + std::to_string(a.unique_id) +
                       ", which has " + std::to_string(att.size());
            if (!stored_values(att, avi, a.components, a.values.data() + p * static_cast<size_t>(a.components)))
                return "attribute " + std::to_string(a.unique_id) + " has values of a type that cannot be read";
        }
        out->attributes.push_back(std::move(a));
    }
    return {};
}

}  // namespace

std::string decode_draco_mesh(const unsigned char* data, size_t size, size_t max_values, DracoMesh* out) {
    *out = DracoMesh{};
    try {  // Draco bounds its allocations by the data's size; a failed one still must not escape
        std::string why = decode(data, size, max_values, out);
        if (!why.empty()) *out = DracoMesh{};
        return why;
    } catch (const std::exception& e) {
        *out = DracoMesh{};
        return std::string("does not decode (") + e.what() + ")";
    }
}

}  // namespace aloha
