// glTF accessor and material features exporters use: sparse accessors (over dense data, and over the
// implicit zeros of an accessor with no buffer view, as morph targets are written), KHR_texture_transform on
// the base colour texture, and meshes bound in a space other than the skeleton's rest space (a mesh in
// centimetres bound by scaled inverse bind matrices). Expected values are worked out in the comments.
#include "engine/assets/gltf_loader.hpp"
#include "tests/common/skinned_cylinder.hpp"

#include <gtest/gtest.h>

#include <cstring>

namespace aloha {
namespace {

using nlohmann::json;
using test::GltfBuilder;
using test::SkinnedCylinder;

Result<GltfCharacter> load(GltfBuilder& b) { return parse_gltf_character(b.dump(), "fixture.gltf"); }

template <class T>
std::vector<unsigned char> bytes_of(const std::vector<T>& v) {
    std::vector<unsigned char> out(v.size() * sizeof(T));
    std::memcpy(out.data(), v.data(), out.size());
    return out;
}

// The cylinder with POSITION replaced by `position` (an accessor index the caller made).
GltfBuilder cylinder_with_position(const SkinnedCylinder& c, const std::function<int(GltfBuilder&)>& position, json* attributes_out = nullptr) {
    GltfBuilder b;
    json attributes = {{"POSITION", position(b)}, {"NORMAL", b.vec3(c.normals)}, {"TEXCOORD_0", b.vec2(c.uvs)},
                       {"JOINTS_0", b.joints(c.joints)}, {"WEIGHTS_0", b.vec4(c.weights)}};
    test::add_cylinder_character(b, attributes, b.indices(c.indices));
    if (attributes_out) *attributes_out = attributes;
    return b;
}

// Adds `sparse` (indices as unsigned shorts, values as floats) to accessor `accessor`.
void make_sparse(GltfBuilder& b, int accessor, const std::vector<uint16_t>& indices, const std::vector<glm::vec3>& values) {
    std::vector<float> flat;
    for (const glm::vec3& v : values) flat.insert(flat.end(), {v.x, v.y, v.z});
    const int iv = b.view(bytes_of(indices));
    const int vv = b.view(bytes_of(flat));
    b.doc["accessors"][static_cast<size_t>(accessor)]["sparse"] = {
        {"count", indices.size()}, {"indices", {{"bufferView", iv}, {"componentType", 5123}}}, {"values", {{"bufferView", vv}}}};
}

// A dense POSITION accessor with sparse substitutions: vertices 5 and 17 take the sparse values, every
// other vertex keeps its own.
TEST(GltfSparse, SubstitutesValuesOverDenseData) {
    const SkinnedCylinder c;
    GltfBuilder b = cylinder_with_position(c, [&](GltfBuilder& g) {
        const int a = g.vec3(c.positions);
        make_sparse(g, a, {5, 17}, {{0.3f, 1.0f, 0.0f}, {0.0f, 1.5f, 0.3f}});
        return a;
    });
    Result<GltfCharacter> r = load(b);
    ASSERT_TRUE(r.ok()) << r.error().to_string();
    const std::vector<glm::vec3>& p = r.value().meshes[0].positions;
    for (size_t v = 0; v < p.size(); ++v) {
        const glm::vec3 want = v == 5 ? glm::vec3(0.3f, 1.0f, 0.0f) : v == 17 ? glm::vec3(0.0f, 1.5f, 0.3f) : c.positions[v];
        EXPECT_EQ(p[v], want) << "vertex " << v;
    }
}

// A morph target as exporters write it: POSITION deltas with no buffer view (all zeros) and sparse
// values for the two vertices it moves; default weight 0.5 halves them.
TEST(GltfSparse, MorphTargetOverImplicitZeros) {
    const SkinnedCylinder c;
    GltfBuilder b = test::plain_cylinder(c);
    b.doc["accessors"].push_back({{"componentType", 5126}, {"count", c.positions.size()}, {"type", "VEC3"}});
    const int deltas = static_cast<int>(b.doc["accessors"].size() - 1);
    make_sparse(b, deltas, {3, 40}, {{0.0f, 0.2f, 0.0f}, {0.1f, 0.0f, -0.1f}});
    b.doc["meshes"][0]["primitives"][0]["targets"] = json::array({{{"POSITION", deltas}}});
    b.doc["meshes"][0]["weights"] = {0.5};
    Result<GltfCharacter> r = load(b);
    ASSERT_TRUE(r.ok()) << r.error().to_string();
    const std::vector<glm::vec3>& p = r.value().meshes[0].positions;
    for (size_t v = 0; v < p.size(); ++v) {
        const glm::vec3 delta = v == 3 ? glm::vec3(0.0f, 0.1f, 0.0f) : v == 40 ? glm::vec3(0.05f, 0.0f, -0.05f) : glm::vec3(0.0f);
        EXPECT_NEAR(glm::length(p[v] - (c.positions[v] + delta)), 0.0f, 1e-6f) << "vertex " << v;
    }
}

// An accessor with no bufferView reads as zeros that no file byte backs: a tiny file asking for 2^25 of them
// (384 MiB as floats) is refused before anything is allocated, naming the accessor.
TEST(GltfSparse, ZerosNoBufferBacksAreRefused) {
    const SkinnedCylinder c;
    GltfBuilder b = test::plain_cylinder(c);
    b.doc["accessors"].push_back({{"componentType", 5126}, {"count", size_t{1} << 25}, {"type", "VEC3"}});
    const auto deltas = b.doc["accessors"].size() - 1;
    b.doc["meshes"][0]["primitives"][0]["targets"] = json::array({{{"POSITION", deltas}}});
    b.doc["meshes"][0]["weights"] = {0.5};
    Result<GltfCharacter> r = load(b);
    ASSERT_FALSE(r.ok());
    const std::string e = r.error().to_string();
    EXPECT_NE(e.find("accessors[" + std::to_string(deltas) + "]: has no bufferView and 33554432 elements: 402653184 bytes of zeros"), std::string::npos)
        << e;
}

TEST(GltfSparse, MalformedSparseDataIsRefusedNamingIt) {
    const SkinnedCylinder c;
    struct Case {
        std::vector<uint16_t> indices;
        std::function<void(json&)> edit;
        const char* expect;
    };
    const std::vector<Case> cases{
        {{7, 7}, [](json&) {}, "index 1 is 7, not greater than the one before"},
        {{3, 2}, [](json&) {}, "index 1 is 2, not greater than the one before"},
        {{3, 999}, [](json&) {}, "index 1 is 999, past the accessor's count 54"},
        {{3, 4}, [](json& s) { s["count"] = 100; }, "count 100 is not between 1 and the accessor's count 54"},
        {{3, 4}, [](json& s) { s["indices"]["componentType"] = 5126; }, "indices component type is FLOAT"},
        {{3, 4}, [](json& s) { s["values"]["bufferView"] = 999; }, "bufferView 999 is out of range"},
        {{3, 4}, [](json& s) { s["values"]["byteOffset"] = 20; }, "needs 44 bytes of bufferViews"},
    };
    for (const Case& k : cases) {
        GltfBuilder b = cylinder_with_position(c, [&](GltfBuilder& g) {
            const int a = g.vec3(c.positions);
            make_sparse(g, a, k.indices, {{0, 0, 0}, {0, 0, 0}});
            return a;
        });
        k.edit(b.doc["accessors"][0]["sparse"]);
        Result<GltfCharacter> r = load(b);
        ASSERT_FALSE(r.ok()) << k.expect;
        const std::string e = r.error().to_string();
        EXPECT_NE(e.find(k.expect), std::string::npos) << e;
        EXPECT_NE(e.find("accessors[0].sparse"), std::string::npos) << e;
    }
}

// KHR_texture_transform on the base colour texture: uv' = T(offset) R(rotation) S(scale) uv (the
// extension's matrices). Offset (0.5, 0.25), rotation pi/2, scale (2, 0.5): S(u, v) = (2u, 0.5v);
// R(pi/2), columns (cos, sin) and (-sin, cos) = (0, 1) and (-1, 0), gives (-0.5v, 2u); then
// uv' = (0.5 - 0.5v, 0.25 + 2u).
TEST(GltfTextureTransform, OffsetRotationScaleApplied) {
    const SkinnedCylinder c;
    GltfBuilder b = test::plain_cylinder(c);
    b.doc["materials"][0]["pbrMetallicRoughness"]["baseColorTexture"]["extensions"] = {
        {"KHR_texture_transform", {{"offset", {0.5, 0.25}}, {"rotation", 1.5707963267948966}, {"scale", {2.0, 0.5}}}}};
    Result<GltfCharacter> r = load(b);
    ASSERT_TRUE(r.ok()) << r.error().to_string();
    const std::vector<glm::vec2>& uv = r.value().meshes[0].uvs;
    ASSERT_EQ(uv.size(), c.uvs.size());
    for (size_t v = 0; v < uv.size(); ++v) {
        EXPECT_NEAR(uv[v].x, 0.5f - 0.5f * c.uvs[v].y, 1e-6f) << v;
        EXPECT_NEAR(uv[v].y, 0.25f + 2.0f * c.uvs[v].x, 1e-6f) << v;
    }
}

// The extension's texCoord replaces the texture info's: TEXCOORD_1 is read.
TEST(GltfTextureTransform, TexCoordOverrides) {
    const SkinnedCylinder c;
    GltfBuilder b = test::plain_cylinder(c);
    std::vector<glm::vec2> second(c.uvs.size(), glm::vec2(0.75f, 0.125f));
    b.doc["meshes"][0]["primitives"][0]["attributes"]["TEXCOORD_1"] = b.vec2(second);
    b.doc["materials"][0]["pbrMetallicRoughness"]["baseColorTexture"]["extensions"] = {{"KHR_texture_transform", {{"texCoord", 1}}}};
    Result<GltfCharacter> r = load(b);
    ASSERT_TRUE(r.ok()) << r.error().to_string();
    for (const glm::vec2& uv : r.value().meshes[0].uvs) EXPECT_EQ(uv, glm::vec2(0.75f, 0.125f));
}

TEST(GltfTextureTransform, MalformedTransformIsRefusedNamingIt) {
    const SkinnedCylinder c;
    const std::vector<std::pair<json, std::string>> cases{
        {{{"offset", {"a", 1}}}, "'offset' is not an array of two numbers"},
        {{{"scale", {1.0}}}, "'scale' is not an array of two numbers"},
        {{{"rotation", "quarter"}}, "'rotation' is not a number"},
        {{{"scale", {1e300, 1.0}}}, "'scale' is NaN, infinite or out of float range"},
        {{{"texCoord", -1}}, "'texCoord' is not a non-negative integer up to 1000"},
    };
    for (const auto& [ext, expect] : cases) {
        GltfBuilder b = test::plain_cylinder(c);
        b.doc["materials"][0]["pbrMetallicRoughness"]["baseColorTexture"]["extensions"] = {{"KHR_texture_transform", ext}};
        Result<GltfCharacter> r = load(b);
        ASSERT_FALSE(r.ok()) << expect;
        const std::string e = r.error().to_string();
        EXPECT_NE(e.find(expect), std::string::npos) << e;
        EXPECT_NE(e.find("materials[0].pbrMetallicRoughness.baseColorTexture.extensions.KHR_texture_transform"), std::string::npos) << e;
    }
}

// The cylinder written with every vertex (and normal) mapped by `file_of` and bound by inverse bind matrices
// that apply `bind` (the rest inverses times `bind`), loaded: its skinned positions are the plain file's, so
// the loader's move into the rest space must give back the plain vertices, normals and triangles.
Result<GltfCharacter> load_bound(const SkinnedCylinder& c, const glm::mat4& file_of, const glm::mat4& bind) {
    GltfBuilder b;
    const glm::mat3 normal_of = glm::transpose(glm::inverse(glm::mat3(file_of)));
    std::vector<glm::vec3> positions, normals;
    for (size_t v = 0; v < c.positions.size(); ++v) {
        positions.push_back(glm::vec3(file_of * glm::vec4(c.positions[v], 1.0f)));
        normals.push_back(glm::normalize(normal_of * c.normals[v]));
    }
    const json attributes = {{"POSITION", b.vec3(positions)}, {"NORMAL", b.vec3(normals)}, {"TEXCOORD_0", b.vec2(c.uvs)}, {"JOINTS_0", b.joints(c.joints)},
                             {"WEIGHTS_0", b.vec4(c.weights)}};
    test::add_cylinder_character(b, attributes, b.indices(c.indices), json::object(), bind);
    return load(b);
}

void expect_plain_mesh(const GltfCharacter& got, const GltfCharacter& want, const SkinnedCylinder& c) {
    const GltfSkinnedMesh& g = got.meshes[0];
    for (size_t v = 0; v < g.positions.size(); ++v) {
        EXPECT_NEAR(glm::length(g.positions[v] - c.positions[v]), 0.0f, 1e-6f) << v;
        EXPECT_NEAR(glm::length(g.normals[v] - c.normals[v]), 0.0f, 1e-6f) << v;
    }
    EXPECT_EQ(g.indices, want.meshes[0].indices);
    for (size_t j = 0; j < 2; ++j)
        for (int col = 0; col < 4; ++col)
            for (int row = 0; row < 4; ++row) EXPECT_NEAR(got.inverse_bind_matrices[j][col][row], want.inverse_bind_matrices[j][col][row], 1e-6f);
    bool noted = false;
    for (const std::string& n : got.notes) noted = noted || n.find("moved into the rest space") != std::string::npos;
    EXPECT_TRUE(noted);
}

// A mesh authored in centimetres (file vertices 100 times the plain ones) bound by matrices that scale by
// 0.01: within float rounding of the 0.01 and 100 products (~1e-7 relative).
TEST(GltfBindSpace, MeshBoundInAnotherSpaceIsMovedIntoTheRestSpace) {
    const SkinnedCylinder c;
    GltfBuilder plain = test::plain_cylinder(c);
    Result<GltfCharacter> want = load(plain);
    ASSERT_TRUE(want.ok()) << want.error().to_string();
    Result<GltfCharacter> got = load_bound(c, glm::scale(glm::mat4(1.0f), glm::vec3(100.0f)), glm::scale(glm::mat4(1.0f), glm::vec3(0.01f)));
    ASSERT_TRUE(got.ok()) << got.error().to_string();
    expect_plain_mesh(got.value(), want.value(), c);
}

// A mirroring bind (file vertices with x negated, bound by matrices that negate x back): the triangles keep
// their winding, since the skinned positions do not change.
TEST(GltfBindSpace, MirroringBindKeepsTheWinding) {
    const SkinnedCylinder c;
    GltfBuilder plain = test::plain_cylinder(c);
    Result<GltfCharacter> want = load(plain);
    ASSERT_TRUE(want.ok()) << want.error().to_string();
    const glm::mat4 mirror = glm::scale(glm::mat4(1.0f), glm::vec3(-1.0f, 1.0f, 1.0f));
    Result<GltfCharacter> got = load_bound(c, mirror, mirror);
    ASSERT_TRUE(got.ok()) << got.error().to_string();
    expect_plain_mesh(got.value(), want.value(), c);
}

// Inverse bind matrices of an accessor without a buffer view read as zeros: singular, so the joints have
// no bind pose, and the file is refused naming the matrix.
TEST(GltfBindSpace, SingularInverseBindIsRefused) {
    const SkinnedCylinder c;
    GltfBuilder b = test::plain_cylinder(c);
    const int ibm = b.doc["skins"][0]["inverseBindMatrices"].get<int>();
    b.doc["accessors"][static_cast<size_t>(ibm)].erase("bufferView");
    Result<GltfCharacter> r = load(b);
    ASSERT_FALSE(r.ok());
    EXPECT_NE(r.error().to_string().find("accessors[" + std::to_string(ibm) + "]: inverse bind matrix 0 is singular"), std::string::npos)
        << r.error().to_string();
}

}  // namespace
}  // namespace aloha
