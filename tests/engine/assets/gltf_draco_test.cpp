// glTF with KHR_draco_mesh_compression: the skinned cylinder of tests/common/skinned_cylinder.hpp encoded here
// with Draco's encoder (positions quantised to 14 bits, normals 10, texture coordinates 12, weights 10; joints
// and connectivity lossless), loaded next to the plain float file and compared as point sets (Draco reorders
// vertices and may merge or split them), then the errors broken Draco data and extension objects give.
#include "engine/assets/gltf_loader.hpp"
#include "tests/common/skinned_cylinder.hpp"
#include "tests/engine/assets/draco_encode.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace aloha {
namespace {

using nlohmann::json;
using test::GltfBuilder;
using test::SkinnedCylinder;

const std::string kDraco = "KHR_draco_mesh_compression";
const std::string kWhere = "meshes[0].primitives[0].extensions.KHR_draco_mesh_compression";

// Quantisation of the encoded cylinder. Draco quantises each attribute over the largest extent of its
// bounding box, so the step is extent / (2^bits - 1) and the rounding error h is half that per component
// (plus 1e-6 of float rounding). Weights: two influences t and 1 - t, each off by at most h, renormalised by
// their sum: t' - t = e1 (1 - t) - t e2 to first order, so still within h (1e-5 covers the second order).
// Measured with Draco 1.5.5: positions 4.9e-5, normals 1.4e-3, texture coordinates 1.2e-4, weights 3.9e-4.
constexpr int kPositionBits = 14, kNormalBits = 10, kTexcoordBits = 12, kWeightBits = 10;
const float kPositionTol = 0.5f * 2.0f / 16383.0f + 1e-6f;  // extent 2 m (the cylinder's height)
const float kTexcoordTol = 0.5f / 4095.0f + 1e-6f;          // extent 1 (u from 0 to 1)
const float kWeightTol = 0.5f / 1023.0f + 1e-5f;            // extent 1
// Octahedral normals: a 10-bit grid over [-1, 1]^2 is 2 / 1023 per step; the octahedron-to-sphere map
// stretches a step by up to about 2 on the unit sphere, so two steps.
const float kNormalTol = 2.0f * 2.0f / 1024.0f;

using Encoded = test::DracoEncoded;

test::DracoBits bits() {
    test::DracoBits b;
    b.position = kPositionBits, b.normal = kNormalBits, b.texcoord = kTexcoordBits, b.generic = kWeightBits;
    return b;
}

Encoded encode(const SkinnedCylinder& c) {
    Encoded e = test::encode_draco_mesh(c.positions, c.normals, c.uvs, c.joints, c.weights, c.indices, bits());
    EXPECT_TRUE(e.error.empty()) << e.error;
    return e;
}

// Accessor types of the compressed file's primitive (the defaults are the plain file's).
struct Types {
    int normal = 5126, texcoord = 5126, joints = 5123, weights = 5126, indices = 5123;
    bool texcoord_normalized = false, weights_normalized = false;
};

// The cylinder character whose primitive carries `bytes` (normally e.bytes) in KHR_draco_mesh_compression;
// its accessors have counts from the decoded mesh and the types `t`, and no bufferView (as the extension's spec
// says), except the indices accessor when `index_stand_in` is set: it then points at the compressed view, as
// some writers do (tinygltf refuses an indices accessor without one; the loader gives it that view itself).
GltfBuilder draco_file(const Encoded& e, const std::vector<unsigned char>& bytes, const Types& t = {}, bool index_stand_in = false) {
    GltfBuilder b;
    const int view = b.view(bytes);
    auto acc = [&b](uint32_t count, const char* type, int component, bool normalized) {
        json a = {{"componentType", component}, {"count", count}, {"type", type}};
        if (normalized) a["normalized"] = true;
        b.doc["accessors"].push_back(a);
        return static_cast<int>(b.doc["accessors"].size() - 1);
    };
    const json attributes = {{"POSITION", acc(e.points, "VEC3", 5126, false)},
                             {"NORMAL", acc(e.points, "VEC3", t.normal, t.normal != 5126)},
                             {"TEXCOORD_0", acc(e.points, "VEC2", t.texcoord, t.texcoord_normalized)},
                             {"JOINTS_0", acc(e.points, "VEC4", t.joints, false)},
                             {"WEIGHTS_0", acc(e.points, "VEC4", t.weights, t.weights_normalized)}};
    const int indices = acc(3 * e.faces, "SCALAR", t.indices, false);
    if (index_stand_in) b.doc["accessors"][indices]["bufferView"] = view;
    test::add_cylinder_character(b, attributes, indices);
    b.doc["meshes"][0]["primitives"][0]["extensions"] = {
        {kDraco,
         {{"bufferView", view},
          {"attributes",
           {{"POSITION", e.position}, {"NORMAL", e.normal}, {"TEXCOORD_0", e.texcoord}, {"JOINTS_0", e.joints}, {"WEIGHTS_0", e.weights}}}}}};
    b.doc["extensionsUsed"] = {kDraco};
    b.doc["extensionsRequired"] = {kDraco};
    if (t.normal != 5126) {  // integer normals come from KHR_mesh_quantization
        b.doc["extensionsUsed"].push_back("KHR_mesh_quantization");
        b.doc["extensionsRequired"].push_back("KHR_mesh_quantization");
    }
    return b;
}

Result<GltfCharacter> load(GltfBuilder& b) { return parse_gltf_character(b.dump(), "fixture.gltf"); }

// Whether vertex `i` of `a` has a vertex in `b` within the tolerances (joints equal).
bool has_match(const GltfSkinnedMesh& a, size_t i, const GltfSkinnedMesh& b, float normal_tol, float uv_tol, float weight_tol) {
    auto near = [](auto x, auto y, float tol) {
        for (int c = 0; c < x.length(); ++c)
            if (std::abs(x[c] - y[c]) > tol) return false;
        return true;
    };
    for (size_t j = 0; j < b.positions.size(); ++j)
        if (near(a.positions[i], b.positions[j], kPositionTol) && near(a.normals[i], b.normals[j], normal_tol) && near(a.uvs[i], b.uvs[j], uv_tol) &&
            a.joints[i] == b.joints[j] && near(a.weights[i], b.weights[j], weight_tol))
            return true;
    return false;
}

// The compressed file against the plain one: same triangle count, and the vertices match both ways.
void expect_same_points(const GltfCharacter& got, const GltfCharacter& want, float normal_tol, float uv_tol, float weight_tol) {
    ASSERT_EQ(got.meshes.size(), 1u);
    ASSERT_EQ(want.meshes.size(), 1u);
    const GltfSkinnedMesh& g = got.meshes[0];
    const GltfSkinnedMesh& w = want.meshes[0];
    EXPECT_EQ(g.indices.size(), w.indices.size());
    ASSERT_EQ(g.uvs.size(), g.positions.size());
    for (size_t v = 0; v < w.positions.size(); ++v) EXPECT_TRUE(has_match(w, v, g, normal_tol, uv_tol, weight_tol)) << "plain vertex " << v;
    for (size_t v = 0; v < g.positions.size(); ++v) EXPECT_TRUE(has_match(g, v, w, normal_tol, uv_tol, weight_tol)) << "decoded vertex " << v;
    EXPECT_EQ(got.skeleton.joints.size(), want.skeleton.joints.size());
}

TEST(GltfDraco, SkinnedCylinderMatchesThePlainFile) {
    const SkinnedCylinder c;  // 54 vertices, 80 triangles
    const Encoded e = encode(c);
    ASSERT_GT(e.points, 0u);
    EXPECT_EQ(e.faces * 3, c.indices.size());
    GltfBuilder plain = test::plain_cylinder(c), compressed = draco_file(e, e.bytes);
    Result<GltfCharacter> want = load(plain), got = load(compressed);
    ASSERT_TRUE(want.ok()) << want.error().to_string();
    ASSERT_TRUE(got.ok()) << got.error().to_string();
    expect_same_points(got.value(), want.value(), kNormalTol, kTexcoordTol, kWeightTol);
    bool noted = false;
    for (const std::string& n : got.value().notes) noted = noted || n == "KHR_draco_mesh_compression: 1 primitive decoded (Draco)";
    EXPECT_TRUE(noted);
}

// The decoded floats and integers converted to the accessors' types: normals to normalized bytes
// (KHR_mesh_quantization), texture coordinates to normalized unsigned shorts, weights to normalized unsigned
// bytes, Draco's 16-bit joints to unsigned bytes, indices to unsigned bytes. Each tolerance grows by half a
// step of its type (round(v * max)).
TEST(GltfDraco, ConvertsToTheAccessorTypes) {
    const SkinnedCylinder c;
    const Encoded e = encode(c);
    Types t;
    t.normal = 5120, t.texcoord = 5123, t.texcoord_normalized = true, t.joints = 5121, t.weights = 5121, t.weights_normalized = true, t.indices = 5121;
    GltfBuilder plain = test::plain_cylinder(c), compressed = draco_file(e, e.bytes, t);
    Result<GltfCharacter> want = load(plain), got = load(compressed);
    ASSERT_TRUE(want.ok()) << want.error().to_string();
    ASSERT_TRUE(got.ok()) << got.error().to_string();
    // Weights: half a byte step per influence, twice over after renormalising two influences.
    expect_same_points(got.value(), want.value(), kNormalTol + 2.0f / 127.0f, kTexcoordTol + 0.5f / 65535.0f, kWeightTol + 2.0f / 255.0f);
}

// A primitive without indices gets an index accessor of its own for the decoded triangles.
TEST(GltfDraco, PrimitiveWithoutIndicesGetsThem) {
    const SkinnedCylinder c;
    const Encoded e = encode(c);
    GltfBuilder plain = test::plain_cylinder(c), compressed = draco_file(e, e.bytes);
    compressed.doc["meshes"][0]["primitives"][0].erase("indices");
    Result<GltfCharacter> want = load(plain), got = load(compressed);
    ASSERT_TRUE(got.ok()) << got.error().to_string();
    expect_same_points(got.value(), want.value(), kNormalTol, kTexcoordTol, kWeightTol);
}

// The extension may name attributes the primitive does not list (the spec forbids it, but Khronos' Box sample
// in glTF-Draco does): with no accessor to fill, they are left out, and a Draco attribute the primitive does not
// name at all (here: TEXCOORD_0) is not read; the primitive's plain data stays.
TEST(GltfDraco, AttributesOutsideThePrimitive) {
    const SkinnedCylinder c;
    const Encoded e = encode(c);
    GltfBuilder b = draco_file(e, e.bytes);
    json& ext = b.doc["meshes"][0]["primitives"][0]["extensions"][kDraco];
    ext["attributes"]["COLOR_0"] = e.position;
    ext["attributes"].erase("TEXCOORD_0");
    // TEXCOORD_0 then needs data of its own: constant (0.25, 0.5) for every decoded point.
    const int uv = b.vec2(std::vector<glm::vec2>(e.points, glm::vec2(0.25f, 0.5f)));
    b.doc["meshes"][0]["primitives"][0]["attributes"]["TEXCOORD_0"] = uv;
    Result<GltfCharacter> got = load(b);
    ASSERT_TRUE(got.ok()) << got.error().to_string();
    ASSERT_EQ(got.value().meshes.size(), 1u);
    for (const glm::vec2& t : got.value().meshes[0].uvs) EXPECT_EQ(t, glm::vec2(0.25f, 0.5f));
}

// Every other fixture's indices accessor has no bufferView, as the extension's spec says; a writer may give it
// the compressed view as a stand-in, which the decoded indices replace all the same.
TEST(GltfDraco, IndicesAccessorWithAStandInView) {
    const SkinnedCylinder c;
    const Encoded e = encode(c);
    GltfBuilder plain = test::plain_cylinder(c), compressed = draco_file(e, e.bytes, {}, true);
    Result<GltfCharacter> want = load(plain), got = load(compressed);
    ASSERT_TRUE(want.ok()) << want.error().to_string();
    ASSERT_TRUE(got.ok()) << got.error().to_string();
    expect_same_points(got.value(), want.value(), kNormalTol, kTexcoordTol, kWeightTol);
}

// Loads `b`, expects an error naming the primitive's extension and containing `part`.
void expect_error(GltfBuilder& b, const std::string& part) {
    Result<GltfCharacter> r = load(b);
    ASSERT_FALSE(r.ok());
    const std::string text = r.error().to_string();
    EXPECT_NE(text.find(kWhere), std::string::npos) << text;
    EXPECT_NE(text.find(part), std::string::npos) << text;
}

TEST(GltfDracoErrors, TruncatedOrCorruptData) {
    const Encoded e = encode(SkinnedCylinder());
    std::vector<unsigned char> half(e.bytes.begin(), e.bytes.begin() + static_cast<std::ptrdiff_t>(e.bytes.size() / 2));
    GltfBuilder truncated = draco_file(e, half);
    expect_error(truncated, "does not decode");
    const std::string text = "not Draco data at all";
    GltfBuilder garbage = draco_file(e, std::vector<unsigned char>(text.begin(), text.end()));
    expect_error(garbage, "is not Draco data");
}

TEST(GltfDracoErrors, BufferViewOutOfRange) {
    const Encoded e = encode(SkinnedCylinder());
    GltfBuilder b = draco_file(e, e.bytes);
    b.doc["meshes"][0]["primitives"][0]["extensions"][kDraco]["bufferView"] = 99;
    expect_error(b, "bufferView 99 is out of range");
    GltfBuilder missing = draco_file(e, e.bytes);
    missing.doc["meshes"][0]["primitives"][0]["extensions"][kDraco].erase("bufferView");
    expect_error(missing, "'bufferView' is missing");
}

TEST(GltfDracoErrors, UnknownAttributeId) {
    const Encoded e = encode(SkinnedCylinder());
    GltfBuilder b = draco_file(e, e.bytes);
    b.doc["meshes"][0]["primitives"][0]["extensions"][kDraco]["attributes"]["NORMAL"] = 17;
    expect_error(b, "attribute NORMAL has Draco id 17, which the decoded mesh does not have");
}

TEST(GltfDracoErrors, CountMismatch) {
    const Encoded e = encode(SkinnedCylinder());
    GltfBuilder b = draco_file(e, e.bytes);
    const int position = b.doc["meshes"][0]["primitives"][0]["attributes"]["POSITION"];
    b.doc["accessors"][position]["count"] = e.points + 1;
    expect_error(b, "has count " + std::to_string(e.points + 1) + ", but the decoded mesh has " + std::to_string(e.points) + " points");
    GltfBuilder idx = draco_file(e, e.bytes);
    const int indices = idx.doc["meshes"][0]["primitives"][0]["indices"];
    idx.doc["accessors"][indices]["count"] = 3;
    expect_error(idx, "indices accessors[" + std::to_string(indices) + "] has count 3");
}

TEST(GltfDracoErrors, PointCloud) {
    const SkinnedCylinder c;
    const Encoded e = encode(c);
    const std::vector<unsigned char> cloud = test::encode_draco_point_cloud(c.positions, bits());
    ASSERT_FALSE(cloud.empty());
    GltfBuilder b = draco_file(e, cloud);
    expect_error(b, "is a point cloud, not a triangle mesh");
}

TEST(GltfDracoErrors, IndicesTooSmallForThePoints) {
    const SkinnedCylinder c(8, 40);  // 328 vertices: more than unsigned bytes index
    const Encoded e = encode(c);
    ASSERT_GT(e.points, 256u);
    Types t;
    t.indices = 5121;
    GltfBuilder b = draco_file(e, e.bytes, t);
    expect_error(b, "too many for the UNSIGNED_BYTE");
}

TEST(GltfDracoErrors, NotTriangles) {
    const Encoded e = encode(SkinnedCylinder());
    GltfBuilder b = draco_file(e, e.bytes);
    b.doc["meshes"][0]["primitives"][0]["mode"] = 0;
    expect_error(b, "mode is 0");
}

// Every truncation and a flipped byte at every offset: each load gives the character or an error, never a crash
// or a hang (the flips may still decode, into other values the loader then checks as usual).
TEST(GltfDracoErrors, DamagedDataNeverCrashes) {
    const Encoded e = encode(SkinnedCylinder());
    size_t errors = 0;
    for (size_t n = 0; n < e.bytes.size(); ++n) {
        GltfBuilder b = draco_file(e, std::vector<unsigned char>(e.bytes.begin(), e.bytes.begin() + static_cast<std::ptrdiff_t>(n)));
        Result<GltfCharacter> r = load(b);
        EXPECT_FALSE(r.ok()) << "truncated to " << n << " bytes";
        for (unsigned char mask : {0x01, 0xFF}) {
            std::vector<unsigned char> flipped = e.bytes;
            flipped[n] = static_cast<unsigned char>(flipped[n] ^ mask);
            GltfBuilder f = draco_file(e, flipped);
            Result<GltfCharacter> fr = load(f);
            if (!fr.ok()) {
                ++errors;
                EXPECT_FALSE(fr.error().to_string().empty());
            }
        }
    }
    EXPECT_GT(errors, 0u);
}

}  // namespace
}  // namespace aloha
