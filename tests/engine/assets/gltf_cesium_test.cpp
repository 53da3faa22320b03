// glTF loader on the Khronos sample CesiumMan.glb (a shared test asset, not in the repository;
// tests/common/test_assets.hpp): counts, bind pose, Y-up folding, clip values. Skips without it.
#include "engine/anim/skeleton.hpp"
#include "engine/assets/gltf_loader.hpp"
#include "tests/common/test_assets.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cstring>
#include <fstream>
#include <iterator>

namespace aloha {
namespace {

struct Loaded {
    GltfCharacter character;
    Skeleton skeleton;
};

// The character at `file`, loaded once per test binary.
const Loaded& load_cesium(const std::string& file) {
    static const Loaded loaded = [&] {
        Loaded l;
        Result<GltfCharacter> r = load_gltf_character(file);
        EXPECT_TRUE(r.ok()) << r.error().to_string();
        if (!r.ok()) return l;
        l.character = std::move(r).value();
        Result<Skeleton> s = build_skeleton(l.character.skeleton, file);
        EXPECT_TRUE(s.ok()) << s.error().to_string();
        if (s.ok()) l.skeleton = std::move(s).value();
        return l;
    }();
    return loaded;
}

// Model-space rest matrices of the runtime skeleton.
std::vector<glm::mat4> rest_model(const Skeleton& s) {
    std::vector<glm::mat4> m(static_cast<size_t>(s.joint_count()));
    for (size_t j = 0; j < m.size(); ++j) {
        glm::mat4 local = glm::mat4_cast(s.rest_rotations()[j]);
        local[0] *= s.rest_scales()[j].x;
        local[1] *= s.rest_scales()[j].y;
        local[2] *= s.rest_scales()[j].z;
        local[3] = glm::vec4(s.rest_translations()[j], 1.0f);
        const int p = s.parents()[j];
        m[j] = p < 0 ? local : m[static_cast<size_t>(p)] * local;
    }
    return m;
}

// The glb's JSON chunk and binary chunk, read independently of tinygltf.
struct Glb {
    nlohmann::json json;
    std::vector<unsigned char> bin;
};

Glb read_glb_file(const std::string& file) {
    std::ifstream in(file, std::ios::binary);
    std::vector<unsigned char> b((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    uint32_t json_len = 0;
    std::memcpy(&json_len, b.data() + 12, 4);
    Glb g;
    g.json = nlohmann::json::parse(b.begin() + 20, b.begin() + 20 + json_len);
    const size_t bin_at = 20 + json_len + 8;
    g.bin.assign(b.begin() + static_cast<long>(bin_at), b.end());
    return g;
}

// First VEC4 float of the output accessor of the `path` channel of animation 0 targeting `node`.
glm::quat first_rotation_key(const Glb& g, int node) {
    for (const auto& ch : g.json["animations"][0]["channels"]) {
        if (ch["target"]["node"] != node || ch["target"]["path"] != "rotation") continue;
        const auto& acc = g.json["accessors"][ch.contains("sampler") ? g.json["animations"][0]["samplers"][ch["sampler"].get<int>()]["output"].get<int>() : 0];
        const auto& bv = g.json["bufferViews"][acc["bufferView"].get<int>()];
        const size_t at = bv.value("byteOffset", size_t{0}) + acc.value("byteOffset", size_t{0});
        float v[4];
        std::memcpy(v, g.bin.data() + at, 16);
        return glm::quat(v[3], v[0], v[1], v[2]);
    }
    ADD_FAILURE() << "no rotation channel for node " << node;
    return {};
}

// Every test needs CesiumMan.glb: SetUp skips the test when it is absent.
class GltfCesium : public ::testing::Test {
protected:
    void SetUp() override {
        ALOHA_REQUIRE_TEST_ASSET(path, "CesiumMan.glb");
        file_ = path;
    }
    const Loaded& cesium() const { return load_cesium(file_); }
    Glb read_glb() const { return read_glb_file(file_); }
    std::string file_;
};

TEST_F(GltfCesium, Counts) {
    const GltfCharacter& c = cesium().character;
    ASSERT_EQ(c.skeleton.joints.size(), 19u);
    EXPECT_EQ(c.skeleton.joints[0].name, "Skeleton_torso_joint_1");
    EXPECT_EQ(c.skeleton.joints[18].name, "leg_joint_R_5");
    EXPECT_EQ(c.skeleton.joints[0].parent, -1);
    EXPECT_EQ(c.inverse_bind_matrices.size(), 19u);
    ASSERT_EQ(c.meshes.size(), 1u);
    const GltfSkinnedMesh& m = c.meshes[0];
    EXPECT_EQ(m.positions.size(), 3273u);
    EXPECT_EQ(m.normals.size(), 3273u);
    EXPECT_EQ(m.joints.size(), 3273u);
    EXPECT_EQ(m.weights.size(), 3273u);
    EXPECT_EQ(m.indices.size(), 4672u * 3u);
    for (size_t v = 0; v < m.positions.size(); ++v) {
        // Sum of four floats each with relative error 2^-24 after division by the sum: < 1e-6.
        EXPECT_NEAR(m.weights[v].x + m.weights[v].y + m.weights[v].z + m.weights[v].w, 1.0f, 1e-6f);
        for (int k = 0; k < 4; ++k) EXPECT_LT(m.joints[v][k], 19);
        EXPECT_NEAR(glm::length(m.normals[v]), 1.0f, 1e-6f);
    }
    // The one note: the mesh binds in the space of its node under Z_UP and Armature, which the loader moves
    // into the skeleton's rest space (BindPoseSkinningReproducesMesh checks the move).
    ASSERT_EQ(c.notes.size(), 1u);
    EXPECT_NE(c.notes[0].find("binds its meshes in a space other than the skeleton's rest space"), std::string::npos) << c.notes[0];
}

TEST_F(GltfCesium, ClipShiftedToZero) {
    const GltfCharacter& c = cesium().character;
    ASSERT_EQ(c.clips.size(), 1u);
    EXPECT_EQ(c.clip_names[0], "clip0");
    EXPECT_EQ(c.clips[0].name, "clip0");
    // First key 0.0416666 s (1/24 s stored as float), last key 2.0 s.
    EXPECT_NEAR(c.clips[0].start_offset, 1.0f / 24.0f, 1e-6f);
    EXPECT_NEAR(c.clips[0].duration, 2.0f - 1.0f / 24.0f, 1e-5f);
    ASSERT_EQ(c.clips[0].tracks.size(), 19u);
    for (const RawJointTracks& t : c.clips[0].tracks) {
        ASSERT_EQ(t.rotations.times.size(), 48u);
        EXPECT_EQ(t.translations.times.size(), 48u);
        EXPECT_EQ(t.scales.times.size(), 48u);
        EXPECT_EQ(t.rotations.times.front(), 0.0f);
    }
}

TEST_F(GltfCesium, RuntimeOrderDiffersFromSkinOrderAndMeshJointsFollowIt) {
    const Loaded& l = cesium();
    bool identity = true;
    for (int r = 0; r < l.skeleton.joint_count(); ++r) identity = identity && l.skeleton.source_index()[static_cast<size_t>(r)] == r;
    EXPECT_FALSE(identity) << "CesiumMan's skin order is not depth-first, so remapping is exercised";
}

TEST_F(GltfCesium, BindPoseSkinningReproducesMesh) {
    const Loaded& l = cesium();
    const std::vector<glm::mat4> model = rest_model(l.skeleton);
    // The mesh node hangs under Z_UP and Armature; per the spec its transform is not applied to
    // skinned vertices, but in the bind pose skinning must equal the static mesh placed by them. The
    // loader moves the vertices into that space (the skeleton's rest space): each loaded vertex is the
    // file's vertex placed by Z_UP * Armature, and skinning at rest leaves it where it is.
    const Glb g = read_glb();
    const auto& pos_accessor = g.json["accessors"][g.json["meshes"][0]["primitives"][0]["attributes"]["POSITION"].get<int>()];
    const auto& pos_view = g.json["bufferViews"][pos_accessor["bufferView"].get<int>()];
    const size_t pos_at = pos_view.value("byteOffset", size_t{0}) + pos_accessor.value("byteOffset", size_t{0});
    const size_t pos_stride = pos_view.value("byteStride", size_t{12});
    auto file_position = [&](size_t v) {
        float p[3];
        std::memcpy(p, g.bin.data() + pos_at + pos_stride * v, 12);
        return glm::vec3(p[0], p[1], p[2]);
    };
    auto node_matrix = [&](int n) {
        glm::mat4 m;
        for (int i = 0; i < 16; ++i) m[i / 4][i % 4] = g.json["nodes"][n]["matrix"][i].get<float>();
        return m;
    };
    const glm::mat4 mesh_world = node_matrix(0) * node_matrix(1);
    const GltfSkinnedMesh& m = l.character.meshes[0];
    float max_err = 0.0f;
    glm::vec3 lo(1e9f), hi(-1e9f);
    for (size_t v = 0; v < m.positions.size(); ++v) {
        glm::vec4 skinned(0.0f);
        for (int k = 0; k < 4; ++k) {
            const size_t j = m.joints[v][k];
            const size_t raw = static_cast<size_t>(l.skeleton.source_index()[j]);
            skinned += m.weights[v][k] * (model[j] * l.character.inverse_bind_matrices[raw] * glm::vec4(m.positions[v], 1.0f));
        }
        max_err = std::max(max_err, glm::length(glm::vec3(skinned) - m.positions[v]));
        max_err = std::max(max_err, glm::length(m.positions[v] - glm::vec3(mesh_world * glm::vec4(file_position(v), 1.0f))));
        lo = glm::min(lo, glm::vec3(skinned));
        hi = glm::max(hi, glm::vec3(skinned));
    }
    EXPECT_LT(max_err, 1e-4f);
    // Height axis after folding Z_UP/Armature: +Y is the longest extent (1.5 m; the T-pose arm
    // span along X is 1.14 m, the body depth along Z about 0.3 m).
    const glm::vec3 size = hi - lo;
    EXPECT_GT(size.y, 1.4f);
    EXPECT_GT(size.y, size.x);
    EXPECT_GT(size.y, 2.0f * size.z);
    const int head = l.skeleton.find("Skeleton_neck_joint_2");
    const int foot = l.skeleton.find("leg_joint_L_5");
    ASSERT_GE(head, 0);
    ASSERT_GE(foot, 0);
    EXPECT_GT(model[static_cast<size_t>(head)][3].y - model[static_cast<size_t>(foot)][3].y, 1.0f) << "head above feet along +Y";
}

TEST_F(GltfCesium, FirstKeyEqualsFileValues) {
    const Loaded& l = cesium();
    const Glb g = read_glb();
    // Non-root joint: no folding, the key is the file's value (quaternion sign may differ).
    const int knee = l.skeleton.find("leg_joint_L_2");  // node 9
    const glm::quat file_knee = first_rotation_key(g, 9);
    EXPECT_NEAR(std::abs(glm::dot(l.character.clips[0].tracks[static_cast<size_t>(knee)].rotations.values[0], glm::normalize(file_knee))), 1.0f, 1e-6f);
    // Root joint (node 3): keys carry the folded Z_UP * Armature rotation.
    glm::mat4 fold(1.0f);
    for (int n : {0, 1}) {
        glm::mat4 m;
        for (int i = 0; i < 16; ++i) m[i / 4][i % 4] = g.json["nodes"][n]["matrix"][i].get<float>();
        fold = fold * m;
    }
    const glm::quat expect = glm::normalize(glm::quat_cast(glm::mat3(fold)) * glm::normalize(first_rotation_key(g, 3)));
    const int root = l.skeleton.find("Skeleton_torso_joint_1");
    EXPECT_NEAR(std::abs(glm::dot(l.character.clips[0].tracks[static_cast<size_t>(root)].rotations.values[0], expect)), 1.0f, 1e-6f);
}

}  // namespace
}  // namespace aloha
