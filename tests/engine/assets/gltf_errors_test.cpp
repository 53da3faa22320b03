// glTF loader on a small hand-written .gltf (embedded base64 buffer) and mutated copies of it.
#include "engine/anim/skeleton.hpp"
#include "engine/assets/gltf_loader.hpp"
#include "tests/common/gltf_builder.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cstring>
#include <fstream>

namespace aloha {
namespace {

using nlohmann::json;

using test::base64;

template <class T>
void append(std::vector<unsigned char>* b, std::initializer_list<T> values) {
    for (T v : values) {
        unsigned char bytes[sizeof(T)];
        std::memcpy(bytes, &v, sizeof(T));
        b->insert(b->end(), bytes, bytes + sizeof(T));
    }
}

// Two joints ("hip" -> "knee" 0.5 m below), one skinned triangle, a 2-key STEP rotation on the
// knee and a channel on the non-joint mesh node. Byte layout of buffer 0:
//   0 positions 3 x vec3 | 36 joints 3 x u16vec4 | 60 weights 3 x vec4 | 108 indices 3 x u16 (+2 pad)
// 116 inverse binds 2 x mat4 | 244 times 2 x float | 252 rotations 2 x vec4 | 284 end
json base_model(std::vector<unsigned char>* joints_bytes = nullptr) {
    std::vector<unsigned char> b;
    append<float>(&b, {0, 0, 0, 1, 0, 0, 0, -1, 0});
    std::vector<unsigned char> joints;
    append<uint16_t>(&joints, {0, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0});
    if (joints_bytes) joints = *joints_bytes;
    b.insert(b.end(), joints.begin(), joints.end());
    append<float>(&b, {1, 0, 0, 0, 2, 0, 0, 0, 0.5f, 0.5f, 0, 0});  // 2nd vertex sums to 2: normalised
    append<uint16_t>(&b, {0, 1, 2, 0});
    append<float>(&b, {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1});
    append<float>(&b, {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0.5f, 0, 1});  // inverse of translate(0,-0.5,0)
    append<float>(&b, {1.0f, 2.0f});
    append<float>(&b, {0, 0, 0, 1, 0.38268343f, 0, 0, 0.92387953f});
    json j;
    j["asset"] = {{"version", "2.0"}};
    j["scene"] = 0;
    j["scenes"] = json::array({{{"nodes", {0, 2}}}});
    j["nodes"] = json::array({{{"name", "hip"}, {"children", {1}}},
                              {{"name", "knee"}, {"translation", {0, -0.5, 0}}},
                              {{"name", "body"}, {"mesh", 0}, {"skin", 0}, {"translation", {5, 0, 0}}}});
    j["skins"] = json::array({{{"joints", {0, 1}}, {"inverseBindMatrices", 4}}});
    j["meshes"] = json::array({{{"primitives", json::array({{{"attributes", {{"POSITION", 0}, {"JOINTS_0", 1}, {"WEIGHTS_0", 2}}}, {"indices", 3}}})}}});
    j["buffers"] = json::array({{{"byteLength", b.size()}, {"uri", "data:application/octet-stream;base64," + base64(b)}}});
    j["bufferViews"] = json::array({{{"buffer", 0}, {"byteOffset", 0}, {"byteLength", 36}},
                                    {{"buffer", 0}, {"byteOffset", 36}, {"byteLength", 24}},
                                    {{"buffer", 0}, {"byteOffset", 60}, {"byteLength", 48}},
                                    {{"buffer", 0}, {"byteOffset", 108}, {"byteLength", 6}},
                                    {{"buffer", 0}, {"byteOffset", 116}, {"byteLength", 128}},
                                    {{"buffer", 0}, {"byteOffset", 244}, {"byteLength", 8}},
                                    {{"buffer", 0}, {"byteOffset", 252}, {"byteLength", 32}}});
    j["accessors"] = json::array({{{"bufferView", 0}, {"componentType", 5126}, {"count", 3}, {"type", "VEC3"}},
                                  {{"bufferView", 1}, {"componentType", 5123}, {"count", 3}, {"type", "VEC4"}},
                                  {{"bufferView", 2}, {"componentType", 5126}, {"count", 3}, {"type", "VEC4"}},
                                  {{"bufferView", 3}, {"componentType", 5123}, {"count", 3}, {"type", "SCALAR"}},
                                  {{"bufferView", 4}, {"componentType", 5126}, {"count", 2}, {"type", "MAT4"}},
                                  {{"bufferView", 5}, {"componentType", 5126}, {"count", 2}, {"type", "SCALAR"}},
                                  {{"bufferView", 6}, {"componentType", 5126}, {"count", 2}, {"type", "VEC4"}}});
    j["animations"] = json::array({{{"name", "bend"},
                                    {"samplers", json::array({{{"input", 5}, {"output", 6}, {"interpolation", "STEP"}}})},
                                    {"channels", json::array({{{"sampler", 0}, {"target", {{"node", 1}, {"path", "rotation"}}}},
                                                              {{"sampler", 0}, {"target", {{"node", 2}, {"path", "rotation"}}}}})}}});
    return j;
}

Result<GltfCharacter> parse(const json& j) { return parse_gltf_character(j.dump(), "test.gltf"); }

TEST(GltfSmall, BaseModelLoads) {
    Result<GltfCharacter> r = parse(base_model());
    ASSERT_TRUE(r.ok()) << r.error().to_string();
    const GltfCharacter& c = r.value();
    ASSERT_EQ(c.skeleton.joints.size(), 2u);
    EXPECT_EQ(c.skeleton.joints[1].parent, 0);
    EXPECT_EQ(c.skeleton.joints[1].translation, glm::vec3(0, -0.5f, 0));
    ASSERT_EQ(c.meshes.size(), 1u);
    EXPECT_EQ(c.meshes[0].weights[1], glm::vec4(1, 0, 0, 0)) << "weights (2,0,0,0) normalised";
    EXPECT_EQ(c.meshes[0].weights[2], glm::vec4(0.5f, 0.5f, 0, 0));
    EXPECT_EQ(c.meshes[0].joints[1][0], 1);
    // No NORMAL attribute: computed; the triangle lies in z = 0 with counter-clockwise winding
    // seen from +z ((1,0,0) x (0,-1,0) = (0,0,-1)), so normals are -z.
    EXPECT_NEAR(c.meshes[0].normals[0].z, -1.0f, 1e-6f);
    // The STEP clip (keys 1 s, 2 s) is shifted to 0 and expanded with a hold key 1e-4 s before 1 s.
    ASSERT_EQ(c.clips.size(), 1u);
    EXPECT_EQ(c.clip_names[0], "bend");
    EXPECT_FLOAT_EQ(c.clips[0].start_offset, 1.0f);
    EXPECT_FLOAT_EQ(c.clips[0].duration, 1.0f);
    const RawTrack<glm::quat>& rot = c.clips[0].tracks[1].rotations;
    ASSERT_EQ(rot.times.size(), 3u);
    EXPECT_NEAR(rot.times[1], 1.0f - 1e-4f, 1e-6f);
    EXPECT_EQ(rot.values[1], rot.values[0]);
    EXPECT_NEAR(rot.values[2].x, 0.38268343f, 1e-7f);
    // One note each: the channel on the non-joint mesh node skipped, vertex 1's weights (sum 2)
    // normalised, the missing NORMAL computed flat.
    ASSERT_EQ(c.notes.size(), 3u);
    auto has = [&](const std::string& part) {
        for (const std::string& n : c.notes)
            if (n.find(part) != std::string::npos) return true;
        return false;
    };
    EXPECT_TRUE(has("nodes[2] is not a joint"));
    EXPECT_TRUE(has("1 vertex in 1 primitive had joint weights not summing to 1; normalised"));
    EXPECT_TRUE(has("1 primitive without NORMAL: flat normals computed"));
}

// Expects parse(j) to fail with `path` in Error::path and `part` in the message.
void expect_error(const json& j, const std::string& path, const std::string& part) {
    Result<GltfCharacter> r = parse(j);
    ASSERT_FALSE(r.ok()) << "expected an error mentioning " << part;
    EXPECT_EQ(r.error().file, "test.gltf");
    EXPECT_NE(r.error().path.find(path), std::string::npos) << r.error().to_string();
    EXPECT_NE(r.error().message.find(part), std::string::npos) << r.error().to_string();
}

TEST(GltfErrors, OutOfRangeAccessorIndex) {
    json j = base_model();
    j["meshes"][0]["primitives"][0]["attributes"]["POSITION"] = 99;
    expect_error(j, "meshes[0].primitives[0].attributes.POSITION", "accessor 99");
}

TEST(GltfErrors, AccessorPastItsBufferView) {
    json j = base_model();
    j["accessors"][0]["count"] = 4;  // 4 x 12 bytes > the view's 36
    expect_error(j, "accessors[0]", "needs 48 bytes of bufferViews[0]");
}

TEST(GltfErrors, WrongAccessorTypeAndComponent) {
    json j = base_model();
    j["accessors"][0]["type"] = "VEC2";
    expect_error(j, "accessors[0]", "type is VEC2, expected VEC3");
    json k = base_model();
    k["accessors"][1]["componentType"] = 5126;
    k["bufferViews"][1]["byteLength"] = 48;
    expect_error(k, "accessors[1]", "component type is FLOAT");
}

TEST(GltfErrors, OutOfRangeJointIndex) {
    std::vector<unsigned char> joints;
    append<uint16_t>(&joints, {0, 0, 0, 0, 7, 0, 0, 0, 1, 0, 0, 0});
    expect_error(base_model(&joints), "JOINTS_0", "vertex 1 uses joint 7, but the skin has 2 joints");
}

TEST(GltfErrors, CyclicHierarchy) {
    json j = base_model();
    j["nodes"][1]["children"] = {0};
    j["scenes"][0]["nodes"] = {2};
    expect_error(j, "nodes[", "cycle");
}

TEST(GltfErrors, MissingBuffer) {
    json j = base_model();
    j["bufferViews"][2]["buffer"] = 3;
    expect_error(j, "bufferViews[2]", "buffer 3 is out of range");
    json k = base_model();
    k["buffers"][0]["uri"] = "missing_buffer.bin";
    Result<GltfCharacter> r = parse_gltf_character(k.dump(), "test.gltf", "/nonexistent");
    ASSERT_FALSE(r.ok());
    EXPECT_EQ(r.error().file, "test.gltf");
    EXPECT_NE(r.error().to_string().find("missing_buffer.bin"), std::string::npos) << r.error().to_string();
}

TEST(GltfErrors, BadValuesAndStructure) {
    json j = base_model();
    j["skins"][0]["joints"] = {0, 0};
    expect_error(j, "skins[0].joints[1]", "listed twice");
    json k = base_model();
    k["skins"] = json::array();
    k["nodes"][2].erase("skin");
    k["nodes"][2].erase("mesh");  // without skins a mesh would make the nodes a skeleton (GltfNodeSkin)
    k["animations"] = json::array();  // and so would animations (an animation file)
    expect_error(k, "skins", "no skins");
    json m = base_model();
    m["nodes"][1]["rotation"] = {0, 0, 0};
    expect_error(m, "nodes[1]", "rotation");
    json n = base_model();
    n["animations"][0]["samplers"][0]["interpolation"] = "BEZIER";
    Result<GltfCharacter> r = parse(n);
    EXPECT_FALSE(r.ok());
    json t = base_model();
    t["animations"][0]["channels"][0]["target"]["node"] = 40;
    expect_error(t, "animations[0].channels[0]", "out of range");
    Result<GltfCharacter> truncated = parse_gltf_character("{\"asset\":{\"version\":\"2.0\"}", "test.gltf");
    ASSERT_FALSE(truncated.ok());
    EXPECT_NE(truncated.error().message.find("not a valid glTF file"), std::string::npos) << truncated.error().to_string();
}

TEST(GltfErrors, MissingFileNamesIt) {
    Result<GltfCharacter> r = load_gltf_character("/nonexistent/man.glb");
    ASSERT_FALSE(r.ok());
    EXPECT_EQ(r.error().file, "/nonexistent/man.glb");
}

}  // namespace
}  // namespace aloha
