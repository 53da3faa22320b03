// glTF as optimisers write it: KHR_mesh_quantization (integer positions, normals and texture coordinates,
// the dequantisation folded into the inverse bind matrices and a KHR_texture_transform, as gltfpack does)
// and EXT_meshopt_compression (buffer views compressed by meshoptimizer, with its octahedral, quaternion and
// exponential filters). Each fixture is the skinned cylinder of tests/common/skinned_cylinder.hpp encoded
// here, and what the loader returns is compared with the plain float file's, within the quantisation step.
#include "engine/assets/gltf_loader.hpp"
#include "tests/common/skinned_cylinder.hpp"

#include <gtest/gtest.h>
#include <meshoptimizer.h>

#include <cstring>
#include <functional>

namespace aloha {
namespace {

using nlohmann::json;
using test::GltfBuilder;
using test::SkinnedCylinder;

template <class T>
std::vector<unsigned char> bytes_of(const std::vector<T>& v) {
    std::vector<unsigned char> out(v.size() * sizeof(T));
    std::memcpy(out.data(), v.data(), out.size());
    return out;
}

bool has_note(const GltfCharacter& c, const std::string& part) {
    for (const std::string& n : c.notes)
        if (n.find(part) != std::string::npos) return true;
    return false;
}

Result<GltfCharacter> load(GltfBuilder& b) { return parse_gltf_character(b.dump(), "fixture.gltf"); }

// Loaded `got` against the plain file's `want`, vertex by vertex (the encodings keep the order): positions
// within `pos_tol` per axis, unit normals within `normal_tol`, texture coordinates within `uv_tol`, joints
// equal, weights within `weight_tol`, same triangles, and inverse bind matrices equal to the plain file's.
void expect_same_character(const GltfCharacter& got, const GltfCharacter& want, float pos_tol, float normal_tol, float uv_tol, float weight_tol) {
    ASSERT_EQ(got.meshes.size(), 1u);
    ASSERT_EQ(want.meshes.size(), 1u);
    const GltfSkinnedMesh& g = got.meshes[0];
    const GltfSkinnedMesh& w = want.meshes[0];
    ASSERT_EQ(g.positions.size(), w.positions.size());
    ASSERT_EQ(g.uvs.size(), w.uvs.size());
    EXPECT_EQ(g.indices, w.indices);
    float pos = 0.0f, nrm = 0.0f, uv = 0.0f, wt = 0.0f;
    for (size_t v = 0; v < g.positions.size(); ++v) {
        for (int c = 0; c < 3; ++c) {
            pos = std::max(pos, std::abs(g.positions[v][c] - w.positions[v][c]));
            nrm = std::max(nrm, std::abs(g.normals[v][c] - w.normals[v][c]));
        }
        for (int c = 0; c < 2; ++c) uv = std::max(uv, std::abs(g.uvs[v][c] - w.uvs[v][c]));
        for (int c = 0; c < 4; ++c) wt = std::max(wt, std::abs(g.weights[v][c] - w.weights[v][c]));
        EXPECT_EQ(g.joints[v], w.joints[v]) << "vertex " << v;
    }
    EXPECT_LE(pos, pos_tol);
    EXPECT_LE(nrm, normal_tol);
    EXPECT_LE(uv, uv_tol);
    EXPECT_LE(wt, weight_tol);
    ASSERT_EQ(got.inverse_bind_matrices.size(), want.inverse_bind_matrices.size());
    for (size_t j = 0; j < got.inverse_bind_matrices.size(); ++j)
        for (int c = 0; c < 4; ++c)
            for (int r = 0; r < 4; ++r) EXPECT_NEAR(got.inverse_bind_matrices[j][c][r], want.inverse_bind_matrices[j][c][r], 1e-4f) << j;
}

// gltfpack's encoding: 14-bit unsigned positions p = min + step * q (the dequantisation D = T(min) S(step) on
// the mesh node and folded into every inverse bind matrix), normalised signed-byte normals, normalised
// unsigned-short texture coordinates uv = offset + scale * q / 65535 (the offset and scale in the material's
// KHR_texture_transform).
TEST(GltfQuantization, QuantisedFileLoadsAsThePlainOne) {
    const SkinnedCylinder c;
    GltfBuilder plain = test::plain_cylinder(c);
    Result<GltfCharacter> want = load(plain);
    ASSERT_TRUE(want.ok()) << want.error().to_string();

    const glm::vec3 min(-0.2f, 0.0f, -0.2f);
    const float step = 2.0f / 16383.0f;  // the largest extent (2 m in y) over 14 bits
    const glm::vec2 uv_min(0.0f, 0.1f), uv_extent(1.0f, 0.8f);
    std::vector<uint16_t> q_pos, q_uv;
    std::vector<int8_t> q_nrm;
    for (size_t v = 0; v < c.positions.size(); ++v) {
        for (int k = 0; k < 3; ++k) q_pos.push_back(static_cast<uint16_t>(std::lround((c.positions[v][k] - min[k]) / step)));
        q_pos.push_back(0);  // 8-byte elements: vertex attributes are 4-byte aligned
        for (int k = 0; k < 3; ++k) q_nrm.push_back(static_cast<int8_t>(std::lround(c.normals[v][k] * 127.0f)));
        q_nrm.push_back(0);  // 4-byte aligned elements, as gltfpack writes them
        for (int k = 0; k < 2; ++k) q_uv.push_back(static_cast<uint16_t>(std::lround((c.uvs[v][k] - uv_min[k]) / uv_extent[k] * 65535.0f)));
    }
    GltfBuilder b;
    const int pos = b.accessor_on(b.view(bytes_of(q_pos), 8), c.positions.size(), "VEC3", 5123);
    const int nrm = b.accessor_on(b.view(bytes_of(q_nrm), 4), c.normals.size(), "VEC3", 5120, true);
    const int uv = b.accessor(q_uv, "VEC2", 5123, true);
    const json attributes = {{"POSITION", pos}, {"NORMAL", nrm}, {"TEXCOORD_0", uv}, {"JOINTS_0", b.joints(c.joints)}, {"WEIGHTS_0", b.vec4(c.weights)}};
    const glm::mat4 dequantise = glm::scale(glm::translate(glm::mat4(1.0f), min), glm::vec3(step));
    test::add_cylinder_character(b, attributes, b.indices(c.indices), {{"translation", {min.x, min.y, min.z}}, {"scale", {step, step, step}}}, dequantise,
                                 {{"KHR_texture_transform", {{"offset", {uv_min.x, uv_min.y}}, {"scale", {uv_extent.x, uv_extent.y}}}}});
    b.doc["extensionsUsed"] = {"KHR_mesh_quantization", "KHR_texture_transform"};
    b.doc["extensionsRequired"] = {"KHR_mesh_quantization"};
    Result<GltfCharacter> got = load(b);
    ASSERT_TRUE(got.ok()) << got.error().to_string();
    // Positions: half a step per axis, plus float rounding of D and its inverse at 2 m (~1e-6). Normals:
    // half a step of 1/127 per component, moved at most that much again by renormalising. Texture
    // coordinates: half a step of 1/65535 of the larger extent (1 in u), plus float rounding.
    expect_same_character(got.value(), want.value(), 0.5f * step + 2e-6f, 1.0f / 127.0f, 0.5f / 65535.0f + 1e-6f, 0.0f);
    EXPECT_TRUE(has_note(got.value(), "binds its meshes in a space other than the skeleton's rest space"));
    EXPECT_TRUE(has_note(got.value(), "KHR_mesh_quantization: integer vertex data read"));
    EXPECT_TRUE(has_note(got.value(), "KHR_texture_transform applied to the texture coordinates of 1 material"));
    EXPECT_FALSE(has_note(want.value(), "binds its meshes"));
}

// Without KHR_mesh_quantization in the file, integer texture coordinates are normalised (the core spec
// allows only normalised ones) and a signed type is refused, naming the accessor.
TEST(GltfQuantization, CoreFileKeepsTheCoreRulesForTextureCoordinates) {
    const SkinnedCylinder c;
    GltfBuilder b;
    std::vector<int16_t> q_uv;
    for (const glm::vec2& uv : c.uvs) q_uv.insert(q_uv.end(), {static_cast<int16_t>(uv.x * 100.0f), static_cast<int16_t>(uv.y * 100.0f)});
    const json attributes = {{"POSITION", b.vec3(c.positions)}, {"NORMAL", b.vec3(c.normals)}, {"TEXCOORD_0", b.accessor(q_uv, "VEC2", 5122)},
                             {"JOINTS_0", b.joints(c.joints)}, {"WEIGHTS_0", b.vec4(c.weights)}};
    test::add_cylinder_character(b, attributes, b.indices(c.indices));
    Result<GltfCharacter> r = load(b);
    ASSERT_FALSE(r.ok());
    EXPECT_NE(r.error().to_string().find("component type is SHORT, expected FLOAT or UNSIGNED_BYTE or UNSIGNED_SHORT"), std::string::npos)
        << r.error().to_string();
    EXPECT_NE(r.error().to_string().find("TEXCOORD_0"), std::string::npos);
}

// EXT_meshopt_compression: every vertex stream, the indices and an animation compressed with meshoptimizer's
// codecs (normals through its octahedral filter, rotations through its quaternion filter, key times through
// its exponential filter), the uncompressed fallback views left full of 0xEE bytes that must not be read.
class GltfMeshopt : public ::testing::Test {
protected:
    // Adds a compressed view of `raw` (count elements of `stride` bytes, mode ATTRIBUTES/TRIANGLES, filter);
    // the view's own bytes are the fallback.
    int compressed_view(GltfBuilder& b, const std::vector<unsigned char>& raw, size_t count, size_t stride, const std::string& mode,
                        const std::string& filter = "NONE", bool vertex_stride = true) {
        std::vector<unsigned char> packed;
        if (mode == "TRIANGLES") {
            std::vector<unsigned int> idx(count);
            for (size_t i = 0; i < count; ++i) {
                uint16_t v;
                std::memcpy(&v, raw.data() + i * 2, 2);
                idx[i] = v;
            }
            packed.resize(meshopt_encodeIndexBufferBound(count, 1 << 16));
            packed.resize(meshopt_encodeIndexBuffer(packed.data(), packed.size(), idx.data(), count));
        } else {
            packed.resize(meshopt_encodeVertexBufferBound(count, stride));
            packed.resize(meshopt_encodeVertexBuffer(packed.data(), packed.size(), raw.data(), count, stride));
        }
        const int source = b.view(packed);
        const int fallback = b.view(std::vector<unsigned char>(count * stride, 0xEE), vertex_stride && mode == "ATTRIBUTES" ? stride : 0);
        json& v = b.doc["bufferViews"][static_cast<size_t>(fallback)];
        json& src = b.doc["bufferViews"][static_cast<size_t>(source)];
        v["extensions"] = {{"EXT_meshopt_compression",
                            {{"buffer", 0}, {"byteOffset", src["byteOffset"]}, {"byteLength", src["byteLength"]}, {"byteStride", stride},
                             {"count", count}, {"mode", mode}, {"filter", filter}}}};
        return fallback;
    }

    // The cylinder compressed, with a clip "bend" turning the tip about z over three keys.
    GltfBuilder compressed(const SkinnedCylinder& c) {
        GltfBuilder b;
        const size_t n = c.positions.size();
        std::vector<float> normals4;
        for (const glm::vec3& v : c.normals) normals4.insert(normals4.end(), {v.x, v.y, v.z, 0.0f});
        std::vector<int8_t> oct(n * 4);
        meshopt_encodeFilterOct(oct.data(), n, 4, 8, normals4.data());
        const json attributes = {
            {"POSITION", b.accessor_on(compressed_view(b, bytes_of(c.positions), n, 12, "ATTRIBUTES"), n, "VEC3", 5126)},
            {"NORMAL", b.accessor_on(compressed_view(b, bytes_of(oct), n, 4, "ATTRIBUTES", "OCTAHEDRAL"), n, "VEC3", 5120, true)},
            {"TEXCOORD_0", b.accessor_on(compressed_view(b, bytes_of(c.uvs), n, 8, "ATTRIBUTES"), n, "VEC2", 5126)},
            {"JOINTS_0", b.accessor_on(compressed_view(b, bytes_of(c.joints), n, 8, "ATTRIBUTES"), n, "VEC4", 5123)},
            {"WEIGHTS_0", b.accessor_on(compressed_view(b, bytes_of(c.weights), n, 16, "ATTRIBUTES"), n, "VEC4", 5126)}};
        const int indices = b.accessor_on(compressed_view(b, bytes_of(c.indices), c.indices.size(), 2, "TRIANGLES", "NONE", false), c.indices.size(),
                                          "SCALAR", 5123);
        test::add_cylinder_character(b, attributes, indices);
        std::vector<uint32_t> times_exp(3);
        meshopt_encodeFilterExp(times_exp.data(), 3, 4, 24, kTimes.data());
        std::vector<int16_t> quats(3 * 4);
        meshopt_encodeFilterQuat(quats.data(), 3, 8, 12, &kRotations[0].x);
        const int input = b.accessor_on(compressed_view(b, bytes_of(times_exp), 3, 4, "ATTRIBUTES", "EXPONENTIAL", false), 3, "SCALAR", 5126);
        const int output = b.accessor_on(compressed_view(b, bytes_of(quats), 3, 8, "ATTRIBUTES", "QUATERNION", false), 3, "VEC4", 5122, true);
        b.doc["animations"] = json::array({{{"name", "bend"},
                                            {"samplers", json::array({{{"input", input}, {"output", output}}})},
                                            {"channels", json::array({{{"sampler", 0}, {"target", {{"node", 0}, {"path", "rotation"}}}}})}}});
        b.doc["extensionsUsed"] = {"EXT_meshopt_compression", "KHR_mesh_quantization"};
        b.doc["extensionsRequired"] = {"EXT_meshopt_compression", "KHR_mesh_quantization"};
        return b;
    }

    // glTF quaternions (x, y, z, w): 0, 30 and 60 degrees about z.
    const std::vector<float> kTimes{0.0f, 0.5f, 1.25f};
    const std::vector<glm::vec4> kRotations{{0, 0, 0, 1}, {0, 0, 0.25881905f, 0.96592583f}, {0, 0, 0.5f, 0.8660254f}};
};

TEST_F(GltfMeshopt, CompressedFileLoadsAsThePlainOne) {
    const SkinnedCylinder c;
    GltfBuilder plain = test::plain_cylinder(c);
    Result<GltfCharacter> want = load(plain);
    ASSERT_TRUE(want.ok()) << want.error().to_string();
    GltfBuilder b = compressed(c);
    Result<GltfCharacter> got = load(b);
    ASSERT_TRUE(got.ok()) << got.error().to_string();
    // The vertex codec is lossless: positions, uvs, joints and weights exactly. Normals: 8-bit octahedral
    // (two signed 8-bit coordinates of the unit octahedron), under 1/127 per component after renormalising,
    // about 2 steps on the sphere at the fold: 2/127.
    expect_same_character(got.value(), want.value(), 0.0f, 2.0f / 127.0f, 0.0f, 0.0f);
    // Five vertex streams, the indices, the key times and the rotations.
    EXPECT_TRUE(has_note(got.value(), "EXT_meshopt_compression: 8 buffer views decoded (meshoptimizer)"));
    ASSERT_EQ(got.value().clips.size(), 1u);
    const RawAnimation& clip = got.value().clips[0];
    EXPECT_EQ(clip.name, "bend");
    size_t tracks = 0;
    for (const RawJointTracks& t : clip.tracks) {
        if (t.rotations.times.empty()) continue;
        ++tracks;
        ASSERT_EQ(t.rotations.times.size(), 3u);
        for (size_t k = 0; k < 3; ++k) {
            // 24-bit mantissas: exact for these times. 12-bit quaternion components: within 1/2047 each
            // (sqrt(2) scale of the three stored ones), so |dq| < 2/2047 and, for unit quaternions,
            // 1 - dot = |dq|^2 / 2 < 4.8e-7.
            EXPECT_FLOAT_EQ(t.rotations.times[k], kTimes[k]);
            const glm::quat q = t.rotations.values[k];
            const float dot = std::abs(q.x * kRotations[k].x + q.y * kRotations[k].y + q.z * kRotations[k].z + q.w * kRotations[k].w);
            EXPECT_GT(dot, 1.0f - 1e-6f) << "key " << k;
        }
    }
    EXPECT_EQ(tracks, 1u);
}

TEST_F(GltfMeshopt, CorruptOrMalformedDataIsRefusedNamingTheView) {
    const SkinnedCylinder c;
    struct Case {
        const char* what;
        std::function<void(json& ext, json& view)> edit;
        const char* expect;
    };
    const std::vector<Case> cases{
        {"header byte", [](json& ext, json&) { ext["byteOffset"] = ext["byteOffset"].get<size_t>() + 1; }, "does not decode as mode ATTRIBUTES"},
        {"truncated", [](json& ext, json&) { ext["byteLength"] = 8; }, "does not decode as mode ATTRIBUTES"},
        {"mode", [](json& ext, json&) { ext["mode"] = "POINTS"; }, "mode 'POINTS' is not ATTRIBUTES, TRIANGLES or INDICES"},
        {"filter", [](json& ext, json&) { ext["filter"] = "WAVELET"; }, "filter 'WAVELET' is not NONE"},
        {"count", [](json& ext, json&) { ext["count"] = 70000000; }, "count 70000000 exceeds the limit"},
        {"count type", [](json& ext, json&) { ext["count"] = -3; }, "'count' is missing or not a positive integer"},
        {"range", [](json& ext, json&) { ext["byteLength"] = size_t{1} << 30; }, "exceeds buffers[0]"},
        {"stride", [](json& ext, json&) { ext["byteStride"] = 6; }, "must be a multiple of 4"},
        {"missing buffer", [](json& ext, json&) { ext.erase("buffer"); }, "'buffer' is missing"},
        {"view length", [](json& ext, json&) { ext["count"] = 55; }, "count x byteStride = 660 bytes, but the buffer view's byteLength is 648"},
        // A count whose output no compressed size can hold (64 decoded bytes a compressed byte at most), refused
        // before anything is allocated.
        {"ratio", [](json& ext, json& view) { ext["count"] = 1000000; view["byteLength"] = 12000000; }, "12000000 bytes cannot decode from"},
    };
    for (const Case& k : cases) {
        GltfBuilder b = compressed(c);
        // The first compressed view is POSITION's fallback, bufferViews[1].
        json& view = b.doc["bufferViews"][1];
        k.edit(view["extensions"]["EXT_meshopt_compression"], view);
        Result<GltfCharacter> r = load(b);
        ASSERT_FALSE(r.ok()) << k.what;
        const std::string e = r.error().to_string();
        EXPECT_NE(e.find(k.expect), std::string::npos) << k.what << ": " << e;
        EXPECT_NE(e.find("bufferViews[1]"), std::string::npos) << k.what << ": " << e;
    }
}

// A file that requires an extension the loader cannot read is refused up front, naming it; extensions it
// reads may be required.
TEST(GltfExtensions, UnsupportedRequiredExtensionIsNamed) {
    const SkinnedCylinder c;
    GltfBuilder b = test::plain_cylinder(c);
    b.doc["extensionsUsed"] = {"KHR_texture_basisu", "KHR_texture_transform"};
    b.doc["extensionsRequired"] = {"KHR_texture_transform", "KHR_texture_basisu"};
    Result<GltfCharacter> r = load(b);
    ASSERT_FALSE(r.ok());
    EXPECT_NE(r.error().to_string().find("requires extension KHR_texture_basisu: only PNG, JPEG and WebP images are decoded"), std::string::npos)
        << r.error().to_string();
    b.doc["extensionsRequired"] = {"EXT_made_up_thing"};
    r = load(b);
    ASSERT_FALSE(r.ok());
    EXPECT_NE(r.error().to_string().find("requires extension EXT_made_up_thing"), std::string::npos) << r.error().to_string();
    b.doc["extensionsRequired"] = {"KHR_texture_transform", "KHR_mesh_quantization"};
    EXPECT_TRUE(load(b).ok());
}

}  // namespace
}  // namespace aloha
