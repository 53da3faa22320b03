// Draco encoding for the loader's tests (see draco_encode.hpp).
#include "tests/engine/assets/draco_encode.hpp"

#include <draco/compression/decode.h>
#include <draco/compression/encode.h>
#include <draco/mesh/mesh.h>

namespace aloha::test {

namespace {

// Adds `values` (point-count elements of `comps` components of `dt`) as an identity-mapped attribute; returns its unique id.
int add_attribute(draco::PointCloud* pc, draco::GeometryAttribute::Type type, int comps, draco::DataType dt, const void* values) {
    const auto elem = static_cast<size_t>(draco::DataTypeLength(dt) * comps);
    draco::GeometryAttribute ga;
    ga.Init(type, nullptr, static_cast<uint8_t>(comps), dt, false, static_cast<int64_t>(elem), 0);
    const int id = pc->AddAttribute(ga, true, pc->num_points());
    for (uint32_t i = 0; i < pc->num_points(); ++i)
        pc->attribute(id)->SetAttributeValue(draco::AttributeValueIndex(i), static_cast<const unsigned char*>(values) + i * elem);
    return static_cast<int>(pc->attribute(id)->unique_id());
}

draco::Encoder encoder(const DracoBits& bits) {
    draco::Encoder enc;
    enc.SetAttributeQuantization(draco::GeometryAttribute::POSITION, bits.position);
    enc.SetAttributeQuantization(draco::GeometryAttribute::NORMAL, bits.normal);
    enc.SetAttributeQuantization(draco::GeometryAttribute::TEX_COORD, bits.texcoord);
    enc.SetAttributeQuantization(draco::GeometryAttribute::GENERIC, bits.generic);
    return enc;
}

std::vector<unsigned char> bytes_of(const draco::EncoderBuffer& buf) {
    return std::vector<unsigned char>(reinterpret_cast<const unsigned char*>(buf.data()), reinterpret_cast<const unsigned char*>(buf.data()) + buf.size());
}

}  // namespace

DracoEncoded encode_draco_mesh(const std::vector<glm::vec3>& positions, const std::vector<glm::vec3>& normals, const std::vector<glm::vec2>& uvs,
                               const std::vector<uint16_t>& joints, const std::vector<glm::vec4>& weights, const std::vector<uint16_t>& indices,
                               const DracoBits& bits) {
    DracoEncoded e;
    draco::Mesh mesh;
    mesh.set_num_points(static_cast<uint32_t>(positions.size()));
    e.position = add_attribute(&mesh, draco::GeometryAttribute::POSITION, 3, draco::DT_FLOAT32, positions.data());
    e.normal = add_attribute(&mesh, draco::GeometryAttribute::NORMAL, 3, draco::DT_FLOAT32, normals.data());
    e.texcoord = add_attribute(&mesh, draco::GeometryAttribute::TEX_COORD, 2, draco::DT_FLOAT32, uvs.data());
    e.joints = add_attribute(&mesh, draco::GeometryAttribute::GENERIC, 4, draco::DT_UINT16, joints.data());
    e.weights = add_attribute(&mesh, draco::GeometryAttribute::GENERIC, 4, draco::DT_FLOAT32, weights.data());
    for (size_t t = 0; t + 2 < indices.size(); t += 3)
        mesh.AddFace({{draco::PointIndex(indices[t]), draco::PointIndex(indices[t + 1]), draco::PointIndex(indices[t + 2])}});
    draco::EncoderBuffer buf;
    const draco::Status s = encoder(bits).EncodeMeshToBuffer(mesh, &buf);
    if (!s.ok()) {
        e.error = "encoding: " + s.error_msg_string();
        return e;
    }
    e.bytes = bytes_of(buf);
    // The accessors must describe the decoded mesh, as exporters write them.
    draco::DecoderBuffer in;
    in.Init(buf.data(), buf.size());
    draco::Decoder decoder;
    auto decoded = decoder.DecodeMeshFromBuffer(&in);
    if (!decoded.ok() || !decoded.value()) {
        e.error = "decoding back: " + decoded.status().error_msg_string();
        return e;
    }
    e.points = decoded.value()->num_points();
    e.faces = decoded.value()->num_faces();
    return e;
}

std::vector<unsigned char> encode_draco_point_cloud(const std::vector<glm::vec3>& positions, const DracoBits& bits) {
    draco::PointCloud pc;
    pc.set_num_points(static_cast<uint32_t>(positions.size()));
    add_attribute(&pc, draco::GeometryAttribute::POSITION, 3, draco::DT_FLOAT32, positions.data());
    draco::EncoderBuffer buf;
    if (!encoder(bits).EncodePointCloudToBuffer(pc, &buf).ok()) return {};
    return bytes_of(buf);
}

}  // namespace aloha::test
