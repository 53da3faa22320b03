// glTF loader features characters use, each on a small fixture built in code (tests/common/
// gltf_builder.hpp): rigid parts under joints, transforms above the armature, several skins,
// weight normalisation, flat normals, morph targets, several primitives and materials, names.
// Expected positions are hand-computed from the fixture's transforms (worked out in comments).
#include "engine/anim/pose.hpp"
#include "engine/anim/skeleton.hpp"
#include "engine/assets/gltf_loader.hpp"
#include "tests/common/gltf_builder.hpp"
#include "tests/common/png_bytes.hpp"

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>
#include <gtest/gtest.h>

#include <cmath>

namespace aloha {
namespace {

using nlohmann::json;
using test::GltfBuilder;

constexpr float kTol = 1e-5f;  // float rounding of a few chained 4x4 products of O(1) values

const float kS45 = std::sqrt(0.5f);  // sin and cos of 45 degrees: a 90-degree quaternion

Result<GltfCharacter> load(GltfBuilder& b) { return parse_gltf_character(b.dump(), "fixture.gltf"); }

// Model matrices of the rest pose of `s` (parents precede children).
std::vector<glm::mat4> rest_model(const Skeleton& s) {
    std::vector<glm::mat4> m(static_cast<size_t>(s.joint_count()));
    for (size_t j = 0; j < m.size(); ++j) {
        const glm::mat4 local = trs_matrix(s.rest_translations()[j], s.rest_rotations()[j], s.rest_scales()[j]);
        m[j] = s.parents()[j] < 0 ? local : m[static_cast<size_t>(s.parents()[j])] * local;
    }
    return m;
}

// Linear-blend skinning of vertex v of `mesh` with runtime model matrices `model`.
glm::vec3 skin(const GltfCharacter& c, const Skeleton& s, const std::vector<glm::mat4>& model, const GltfSkinnedMesh& mesh, size_t v) {
    glm::vec4 out(0.0f);
    for (int k = 0; k < 4; ++k) {
        const uint16_t j = mesh.joints[v][k];
        out += mesh.weights[v][k] * (model[j] * c.inverse_bind_matrices[static_cast<size_t>(s.source_index()[j])] * glm::vec4(mesh.positions[v], 1.0f));
    }
    return glm::vec3(out);
}

void expect_near(glm::vec3 a, glm::vec3 b, float tol = kTol) {
    EXPECT_NEAR(a.x, b.x, tol);
    EXPECT_NEAR(a.y, b.y, tol);
    EXPECT_NEAR(a.z, b.z, tol);
}

const GltfSkinnedMesh* mesh_from(const GltfCharacter& c, const std::string& source) {
    for (const GltfSkinnedMesh& m : c.meshes)
        if (m.source.rfind(source, 0) == 0) return &m;
    return nullptr;
}

bool has_note(const GltfCharacter& c, const std::string& part) {
    for (const std::string& n : c.notes)
        if (n.find(part) != std::string::npos) return true;
    return false;
}

// A triangle primitive in z = 0 with normals +x (to see them turned).
json triangle(GltfBuilder& b) {
    return json::array({{{"attributes", {{"POSITION", b.vec3({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}})}, {"NORMAL", b.vec3({{1, 0, 0}, {1, 0, 0}, {1, 0, 0}})}}}}});
}

// root (0,1,0) -> arm (0.5,0,0), 90 degrees about z -> part (non-joint, (0,0.2,0), scale 2, a mesh);
// the arm node also carries a mesh itself. Skin 0 = {root, arm} with inverse world binds; no skinned mesh.
TEST(GltfRigidParts, FollowTheirJoint) {
    GltfBuilder b;
    const int part = b.node({{"name", "part"}, {"translation", {0, 0.2, 0}}, {"scale", {2, 2, 2}}, {"mesh", b.mesh(triangle(b))}});
    const int arm = b.node({{"name", "arm"}, {"translation", {0.5, 0, 0}}, {"rotation", {0, 0, kS45, kS45}}, {"children", {part}}, {"mesh", b.mesh(triangle(b))}});
    const int root = b.node({{"name", "root"}, {"translation", {0, 1, 0}}, {"children", {arm}}});
    b.root(root);
    const glm::mat4 w_root = glm::translate(glm::mat4(1.0f), glm::vec3(0, 1, 0));
    const glm::mat4 w_arm = w_root * glm::translate(glm::mat4(1.0f), glm::vec3(0.5f, 0, 0)) * glm::mat4_cast(glm::quat(kS45, 0, 0, kS45));
    b.skin({root, arm}, {glm::inverse(w_root), glm::inverse(w_arm)});
    Result<GltfCharacter> r = load(b);
    ASSERT_TRUE(r.ok()) << r.error().to_string();
    const GltfCharacter& c = r.value();
    Result<Skeleton> s = build_skeleton(c.skeleton, "fixture");
    ASSERT_TRUE(s.ok());
    const int arm_j = s.value().find("arm");
    ASSERT_EQ(c.meshes.size(), 2u);
    const GltfSkinnedMesh* p = mesh_from(c, "nodes[0]");
    const GltfSkinnedMesh* a = mesh_from(c, "nodes[1]");
    ASSERT_TRUE(p && a);
    for (size_t v = 0; v < 3; ++v) {
        EXPECT_EQ(p->joints[v][0], arm_j);
        EXPECT_EQ(p->weights[v], glm::vec4(1, 0, 0, 0));
    }
    // Rest: T(0,1,0) T(0.5,0,0) Rz(90) T(0,0.2,0) S(2) v, Rz(90) taking (x, y) to (-y, x):
    //   (0,0,0) -> (0,0.2,0) -> (-0.2,0,0) -> (0.3,1,0);  (1,0,0) -> (2,0.2,0) -> (-0.2,2,0) -> (0.3,3,0);
    //   (0,1,0) -> (0,2.2,0) -> (-2.2,0,0) -> (-1.7,1,0). The arm's own mesh: T(0.5,1,0) Rz(90) v.
    const std::vector<glm::mat4> rest = rest_model(s.value());
    const glm::vec3 part_rest[3] = {{0.3f, 1, 0}, {0.3f, 3, 0}, {-1.7f, 1, 0}};
    const glm::vec3 arm_rest[3] = {{0.5f, 1, 0}, {0.5f, 2, 0}, {-0.5f, 1, 0}};
    for (size_t v = 0; v < 3; ++v) {
        expect_near(skin(c, s.value(), rest, *p, v), part_rest[v]);
        expect_near(skin(c, s.value(), rest, *a, v), arm_rest[v]);
    }
    // Normals +x turned by Rz(90) to +y (bind space here equals world: inverse world binds).
    expect_near(p->normals[0], glm::vec3(0, 1, 0));
    // Posed: the arm moved to M = T(2,0,0) Rx(30); the part follows: M T(0,0.2,0) S(2) v.
    //   (1,0,0) -> (2,0.2,0) -> Rx(30): (2, 0.2 cos30, 0.2 sin30) -> (4, 0.17320508, 0.1).
    std::vector<glm::mat4> posed = rest;
    posed[static_cast<size_t>(arm_j)] = glm::translate(glm::mat4(1.0f), glm::vec3(2, 0, 0)) * glm::rotate(glm::mat4(1.0f), glm::radians(30.0f), glm::vec3(1, 0, 0));
    expect_near(skin(c, s.value(), posed, *p, 1), glm::vec3(4.0f, 0.17320508f, 0.1f));
    expect_near(skin(c, s.value(), posed, *p, 0), glm::vec3(2.0f, 0.17320508f, 0.1f));
}

// A mirrored rigid part (scale -1 in x) keeps its front faces: the triangle's winding is reversed.
TEST(GltfRigidParts, MirroredPartReversesWinding) {
    GltfBuilder b;
    const int part = b.node({{"name", "mirror"}, {"scale", {-1, 1, 1}}, {"mesh", b.mesh(triangle(b))}});
    const int root = b.node({{"name", "root"}, {"children", {part}}});
    b.root(root);
    b.skin({root}, {});
    Result<GltfCharacter> r = load(b);
    ASSERT_TRUE(r.ok()) << r.error().to_string();
    ASSERT_EQ(r.value().meshes.size(), 1u);
    EXPECT_EQ(r.value().meshes[0].indices, (std::vector<uint32_t>{0, 2, 1}));
    expect_near(r.value().meshes[0].positions[1], glm::vec3(-1, 0, 0));
    expect_near(r.value().meshes[0].normals[0], glm::vec3(-1, 0, 0));  // inverse transpose of S(-1,1,1)
}

// A mesh with no skin and no joint above it is left out with a note.
TEST(GltfRigidParts, UnattachedMeshIsNoted) {
    GltfBuilder b;
    const int root = b.node({{"name", "root"}});
    b.root(root);
    b.root(b.node({{"name", "prop"}, {"mesh", b.mesh(triangle(b))}}));
    b.skin({root}, {});
    Result<GltfCharacter> r = load(b);
    ASSERT_TRUE(r.ok()) << r.error().to_string();
    EXPECT_TRUE(r.value().meshes.empty());
    EXPECT_TRUE(has_note(r.value(), "nodes[1]: mesh with no skin and no joint above it; left out"));
}

// Armature node scaled by 100 above joints authored in hundredths (hips 0.01 up, head 0.007 above):
// world hips at 1.0 m, head at 1.7 m; a skinned vertex authored at the head's bind (0, 0.017, 0) in
// armature space lands at 1.7 m; a hips translation key (0, 0.01, 0.005) becomes (0, 1, 0.5).
TEST(GltfArmatureTransforms, Scale100GivesWorldSize) {
    GltfBuilder b;
    const int head = b.node({{"name", "head"}, {"translation", {0, 0.007, 0}}});
    const int hips = b.node({{"name", "hips"}, {"translation", {0, 0.01, 0}}, {"children", {head}}});
    const int armature = b.node({{"name", "Armature"}, {"scale", {100, 100, 100}}, {"children", {hips}}});
    const json prim = {{"attributes",
                        {{"POSITION", b.vec3({{0, 0.017f, 0}, {0.001f, 0.017f, 0}, {0, 0.01f, 0}})},
                         {"JOINTS_0", b.joints({1, 0, 0, 0, 1, 0, 0, 0, 0, 0, 0, 0})},
                         {"WEIGHTS_0", b.vec4({{1, 0, 0, 0}, {1, 0, 0, 0}, {1, 0, 0, 0}})}}}};
    const int body = b.node({{"name", "body"}, {"mesh", b.mesh(json::array({prim}))}, {"skin", 0}, {"translation", {9, 9, 9}}});
    b.root(armature);
    b.root(body);
    // Inverse binds map armature space to joint space (the armature's scale is in the joints' world).
    b.skin({hips, head}, {glm::translate(glm::mat4(1.0f), glm::vec3(0, -0.01f, 0)), glm::translate(glm::mat4(1.0f), glm::vec3(0, -0.017f, 0))});
    const int times = b.scalars({0.0f, 1.0f});
    const int values = b.vec3({{0, 0.01f, 0}, {0, 0.01f, 0.005f}});
    b.doc["animations"] = json::array({{{"samplers", json::array({{{"input", times}, {"output", values}}})},
                                        {"channels", json::array({{{"sampler", 0}, {"target", {{"node", hips}, {"path", "translation"}}}}})}}});
    Result<GltfCharacter> r = load(b);
    ASSERT_TRUE(r.ok()) << r.error().to_string();
    const GltfCharacter& c = r.value();
    Result<Skeleton> s = build_skeleton(c.skeleton, "fixture");
    ASSERT_TRUE(s.ok());
    const std::vector<glm::mat4> rest = rest_model(s.value());
    expect_near(glm::vec3(rest[static_cast<size_t>(s.value().find("hips"))][3]), glm::vec3(0, 1.0f, 0));
    expect_near(glm::vec3(rest[static_cast<size_t>(s.value().find("head"))][3]), glm::vec3(0, 1.7f, 0));
    ASSERT_EQ(c.meshes.size(), 1u);
    // The mesh node's translation (9,9,9) is ignored, as the spec requires for skinned meshes.
    expect_near(skin(c, s.value(), rest, c.meshes[0], 0), glm::vec3(0, 1.7f, 0), 1e-4f);
    expect_near(skin(c, s.value(), rest, c.meshes[0], 1), glm::vec3(0.1f, 1.7f, 0), 1e-4f);
    expect_near(skin(c, s.value(), rest, c.meshes[0], 2), glm::vec3(0, 1.0f, 0), 1e-4f);
    ASSERT_EQ(c.clips.size(), 1u);
    const auto& keys = c.clips[0].tracks[static_cast<size_t>(s.value().find("hips"))].translations.values;
    ASSERT_EQ(keys.size(), 2u);
    expect_near(keys[1], glm::vec3(0, 1.0f, 0.5f), 1e-5f);
}

// Transforms above the joints given as a matrix and as a rotation: Z-up armature (rotation -90
// degrees about x) under a matrix node translating by (1,0,0). A joint at (0,0,1) in Z-up lands at
// (1,1,0) in the Y-up world: Rx(-90) takes (x, y, z) to (x, z, -y).
TEST(GltfArmatureTransforms, MatrixAndRotationAbove) {
    GltfBuilder b;
    const int top = b.node({{"name", "top"}, {"translation", {0, 0, 1}}});
    const int zup = b.node({{"name", "Z_UP"}, {"rotation", {-kS45, 0, 0, kS45}}, {"children", {top}}});
    const int frame = b.node({{"name", "frame"}, {"matrix", {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 1, 0, 0, 1}}, {"children", {zup}}});
    b.root(frame);
    b.skin({top}, {});
    Result<GltfCharacter> r = load(b);
    ASSERT_TRUE(r.ok()) << r.error().to_string();
    Result<Skeleton> s = build_skeleton(r.value().skeleton, "fixture");
    ASSERT_TRUE(s.ok());
    expect_near(glm::vec3(rest_model(s.value())[0][3]), glm::vec3(1, 1, 0));
}

// An animated node above the joints (an "Armature" object moved and turned in Blender, not its root bone):
// its keys are folded into the root joint's. Armature: translation (0,0,0) -> (0,0,2) over 0..1 s and a
// rotation about y 0 -> 90 degrees over 0..1 s; the joint "hips" at rest (0,1,0) with its own rotation
// about x 0 -> 60 degrees over 0..0.5 s; its child "spine" at (0,0.5,0) is not re-keyed. The root joint's
// keys fall at the union of the times (0, 0.5, 1) and equal Armature(t) * hips(t) there, each factor
// sampled as glTF's LINEAR (slerp) prescribes; float rounding of two chained products: 1e-5.
TEST(GltfArmatureTransforms, AnimatedNodeAboveTheJointsMovesThem) {
    GltfBuilder b;
    const int spine = b.node({{"name", "spine"}, {"translation", {0, 0.5, 0}}});
    const int hips = b.node({{"name", "hips"}, {"translation", {0, 1, 0}}, {"children", {spine}}});
    const int armature = b.node({{"name", "Armature"}, {"children", {hips}}});
    b.root(armature);
    b.skin({hips, spine}, {});
    const glm::quat y90 = glm::angleAxis(1.5707963f, glm::vec3(0, 1, 0)), x60 = glm::angleAxis(1.0471976f, glm::vec3(1, 0, 0));
    auto quat4 = [](glm::quat q) { return glm::vec4(q.x, q.y, q.z, q.w); };
    const int t01 = b.scalars({0.0f, 1.0f}), t05 = b.scalars({0.0f, 0.5f});
    const int arm_t = b.vec3({{0, 0, 0}, {0, 0, 2}}), arm_r = b.vec4({quat4(glm::quat(1, 0, 0, 0)), quat4(y90)});
    const int hip_r = b.vec4({quat4(glm::quat(1, 0, 0, 0)), quat4(x60)});
    b.doc["animations"] = json::array({{{"name", "move"},
        {"samplers", json::array({{{"input", t01}, {"output", arm_t}}, {{"input", t01}, {"output", arm_r}}, {{"input", t05}, {"output", hip_r}}})},
        {"channels", json::array({{{"sampler", 0}, {"target", {{"node", armature}, {"path", "translation"}}}},
                                  {{"sampler", 1}, {"target", {{"node", armature}, {"path", "rotation"}}}},
                                  {{"sampler", 2}, {"target", {{"node", hips}, {"path", "rotation"}}}}})}}});
    Result<GltfCharacter> r = load(b);
    ASSERT_TRUE(r.ok()) << r.error().to_string();
    const GltfCharacter& c = r.value();
    ASSERT_EQ(c.clips.size(), 1u);
    const RawJointTracks& root = c.clips[0].tracks[0];
    ASSERT_EQ(root.translations.times, (std::vector<float>{0.0f, 0.5f, 1.0f}));
    ASSERT_EQ(root.rotations.times.size(), 3u);
    for (size_t k = 0; k < 3; ++k) {
        const float t = root.translations.times[k];
        const glm::mat4 arm = glm::translate(glm::mat4(1.0f), glm::vec3(0, 0, 2 * t)) * glm::mat4_cast(glm::slerp(glm::quat(1, 0, 0, 0), y90, t));
        const glm::mat4 hip = glm::translate(glm::mat4(1.0f), glm::vec3(0, 1, 0)) * glm::mat4_cast(glm::slerp(glm::quat(1, 0, 0, 0), x60, std::min(2 * t, 1.0f)));
        const glm::mat4 want = arm * hip;
        expect_near(root.translations.values[k], glm::vec3(want[3]));
        const glm::mat3 got = glm::mat3_cast(root.rotations.values[k]);
        for (int col = 0; col < 3; ++col) expect_near(got[col], glm::vec3(want[col]));
        expect_near(root.scales.values[k], glm::vec3(1.0f));
    }
    EXPECT_TRUE(c.clips[0].tracks[1].translations.values.empty()) << "the child joint keeps its own (no) keys";
    EXPECT_TRUE(has_note(c, "animations[0]: the animation of nodes[2] (above the joints, not joints) is folded into the keys of the 1 joint below"));
}

// A clip "wave" turning node `arm` from 90 degrees about z back to rest over 1 s.
void add_wave(GltfBuilder& b, int arm) {
    const int times = b.scalars({0.0f, 1.0f});
    const int rots = b.vec4({{0, 0, kS45, kS45}, {0, 0, 0, 1}});
    b.doc["animations"] = json::array({{{"name", "wave"}, {"samplers", json::array({{{"input", times}, {"output", rots}}})},
                                        {"channels", json::array({{{"sampler", 0}, {"target", {{"node", arm}, {"path", "rotation"}}}}})}}});
}

// A file without skins (a rigid robot: meshes on an animated node hierarchy): every node of the scene becomes a
// joint bound at its rest pose, each mesh a rigid part of its node, the node animations a clip. body (0,1,0)
// carries a triangle and an arm node (0.5,0,0) turned 90 degrees about z with its own triangle; the arm's
// rotation is animated. Skinned at rest, every vertex lands where its node's world transform puts it.
TEST(GltfNodeSkin, RigidHierarchyWithoutSkinIsTheSkeleton) {
    GltfBuilder b;
    const int arm = b.node({{"name", "arm"}, {"translation", {0.5, 0, 0}}, {"rotation", {0, 0, kS45, kS45}}, {"mesh", b.mesh(triangle(b))}});
    const int body = b.node({{"name", "body"}, {"translation", {0, 1, 0}}, {"children", {arm}}, {"mesh", b.mesh(triangle(b))}});
    b.root(body);
    add_wave(b, arm);
    Result<GltfCharacter> r = load(b);
    ASSERT_TRUE(r.ok()) << r.error().to_string();
    const GltfCharacter& c = r.value();
    ASSERT_EQ(c.skeleton.joints.size(), 2u);
    EXPECT_EQ(c.skeleton.joints[0].name, "body");
    EXPECT_EQ(c.skeleton.joints[1].name, "arm");
    EXPECT_TRUE(has_note(c, "no skin: the 2 nodes of the scene are the skeleton, each mesh a rigid part of its node"));
    Result<Skeleton> s = build_skeleton(c.skeleton, "fixture");
    ASSERT_TRUE(s.ok());
    const std::vector<glm::mat4> model = rest_model(s.value());
    ASSERT_EQ(c.meshes.size(), 2u);
    const GltfSkinnedMesh* arm_mesh = mesh_from(c, "nodes[0]");
    const GltfSkinnedMesh* body_mesh = mesh_from(c, "nodes[1]");
    ASSERT_TRUE(arm_mesh && body_mesh);
    // Body vertices: (0,1,0) + v; arm vertices: (0.5,1,0) + Rz(90) v, Rz(90) taking (x, y) to (-y, x).
    expect_near(skin(c, s.value(), model, *body_mesh, 1), glm::vec3(1, 1, 0));
    expect_near(skin(c, s.value(), model, *arm_mesh, 1), glm::vec3(0.5f, 2, 0));
    expect_near(skin(c, s.value(), model, *arm_mesh, 2), glm::vec3(-0.5f, 1, 0));
    ASSERT_EQ(c.clips.size(), 1u);
    const int arm_joint = s.value().find("arm");
    ASSERT_GE(arm_joint, 0);
    EXPECT_EQ(c.clips[0].tracks[static_cast<size_t>(arm_joint)].rotations.values.size(), 2u);
    // A scene listing the child before its parent (not a root, against the specification): the same skeleton and
    // binding, the child's rest transform taken through its parent.
    b.doc["scenes"][0]["nodes"] = {arm, body};
    Result<GltfCharacter> again = load(b);
    ASSERT_TRUE(again.ok()) << again.error().to_string();
    Result<Skeleton> s2 = build_skeleton(again.value().skeleton, "fixture");
    ASSERT_TRUE(s2.ok());
    const GltfSkinnedMesh* arm_again = mesh_from(again.value(), "nodes[0]");
    ASSERT_TRUE(arm_again);
    expect_near(skin(again.value(), s2.value(), rest_model(s2.value()), *arm_again, 1), glm::vec3(0.5f, 2, 0));
}

// An animation file (a Blender armature exported without its mesh: nodes and animations, no skin, no mesh): the
// scene's nodes are the skeleton and its animations the clips, so it can be a motion file (docs/SCENES.md).
TEST(GltfNodeSkin, AnimationFileWithoutSkinOrMeshIsASkeletonWithClips) {
    GltfBuilder b;
    const int arm = b.node({{"name", "arm"}, {"translation", {0.5, 0, 0}}});
    const int body = b.node({{"name", "body"}, {"translation", {0, 1, 0}}, {"children", {arm}}});
    b.root(body);
    add_wave(b, arm);
    Result<GltfCharacter> r = load(b);
    ASSERT_TRUE(r.ok()) << r.error().to_string();
    const GltfCharacter& c = r.value();
    ASSERT_EQ(c.skeleton.joints.size(), 2u);
    EXPECT_TRUE(c.meshes.empty());
    ASSERT_EQ(c.clips.size(), 1u);
    EXPECT_EQ(c.clip_names[0], "wave");
    EXPECT_TRUE(has_note(c, "no skin and no mesh (an animation file): the 2 nodes of the scene are the skeleton, its animations the clips"));
}

// Two skins share joint `a`: skin 0 = {root, a}, skin 1 = {a, b}. Skin 1 binds its mesh in a space
// shifted by (1,0,0): its inverse binds are inverse(world bind) * T(1,0,0). A skin-1 vertex at v
// weighted half a, half b must skin exactly as the spec's formula with skin 1's own matrices.
TEST(GltfSkins, TwoSkinsShareJoints) {
    GltfBuilder b;
    const int jb = b.node({{"name", "b"}, {"translation", {0, 0.5, 0}}});
    const int ja = b.node({{"name", "a"}, {"translation", {0, 0.5, 0}}, {"children", {jb}}});
    const int root = b.node({{"name", "root"}, {"translation", {0, 1, 0}}, {"children", {ja}}});
    auto prim = [&](std::vector<uint16_t> joints) {
        return json::array({{{"attributes",
                              {{"POSITION", b.vec3({{0, 1.6f, 0}, {0.1f, 1.8f, 0}, {0, 2.0f, 0.1f}})},
                               {"JOINTS_0", b.joints(joints)},
                               {"WEIGHTS_0", b.vec4({{0.5f, 0.5f, 0, 0}, {0.5f, 0.5f, 0, 0}, {1, 0, 0, 0}})}}}}});
    };
    const int body0 = b.node({{"name", "body0"}, {"mesh", b.mesh(prim({0, 1, 0, 0, 0, 1, 0, 0, 1, 0, 0, 0}))}, {"skin", 0}});
    const int body1 = b.node({{"name", "body1"}, {"mesh", b.mesh(prim({0, 1, 0, 0, 0, 1, 0, 0, 1, 0, 0, 0}))}, {"skin", 1}});
    b.root(root);
    b.root(body0);
    b.root(body1);
    const glm::mat4 w_root = glm::translate(glm::mat4(1.0f), glm::vec3(0, 1, 0));
    const glm::mat4 w_a = glm::translate(glm::mat4(1.0f), glm::vec3(0, 1.5f, 0));
    const glm::mat4 w_b = glm::translate(glm::mat4(1.0f), glm::vec3(0, 2.0f, 0));
    const glm::mat4 shift = glm::translate(glm::mat4(1.0f), glm::vec3(1, 0, 0));
    b.skin({root, ja}, {glm::inverse(w_root), glm::inverse(w_a)});
    const std::vector<glm::mat4> ibm1 = {glm::inverse(w_a) * shift, glm::inverse(w_b) * shift};
    b.skin({ja, jb}, ibm1);
    Result<GltfCharacter> r = load(b);
    ASSERT_TRUE(r.ok()) << r.error().to_string();
    const GltfCharacter& c = r.value();
    ASSERT_EQ(c.skeleton.joints.size(), 3u) << "root, a, b: the union, a once";
    Result<Skeleton> s = build_skeleton(c.skeleton, "fixture");
    ASSERT_TRUE(s.ok());
    const GltfSkinnedMesh* m1 = mesh_from(c, "nodes[4]");
    ASSERT_TRUE(m1);
    const int ra = s.value().find("a"), rb = s.value().find("b");
    // Any pose: model matrices of a and b rotated and moved differently.
    std::vector<glm::mat4> pose = rest_model(s.value());
    pose[static_cast<size_t>(ra)] = glm::translate(glm::mat4(1.0f), glm::vec3(0.2f, 1.4f, 0)) * glm::rotate(glm::mat4(1.0f), 0.4f, glm::vec3(0, 0, 1));
    pose[static_cast<size_t>(rb)] = glm::translate(glm::mat4(1.0f), glm::vec3(-0.3f, 2.1f, 0.2f)) * glm::rotate(glm::mat4(1.0f), -0.7f, glm::vec3(1, 0, 0));
    const glm::vec3 file_positions[3] = {{0, 1.6f, 0}, {0.1f, 1.8f, 0}, {0, 2.0f, 0.1f}};
    const glm::vec4 file_weights[3] = {{0.5f, 0.5f, 0, 0}, {0.5f, 0.5f, 0, 0}, {1, 0, 0, 0}};
    const int file_joints[3][2] = {{ra, rb}, {ra, rb}, {rb, ra}};  // skin-1 joint 0 = a, 1 = b
    const glm::mat4 ibm_of[2] = {ibm1[0], ibm1[1]};
    for (size_t v = 0; v < 3; ++v) {
        // The spec's formula with skin 1's own inverse binds.
        glm::vec4 want(0.0f);
        for (int k = 0; k < 2; ++k) {
            const int j = file_joints[v][k];
            want += file_weights[v][k] * (pose[static_cast<size_t>(j)] * ibm_of[j == ra ? 0 : 1] * glm::vec4(file_positions[v], 1.0f));
        }
        expect_near(skin(c, s.value(), pose, *m1, v), glm::vec3(want), 1e-5f);
        // At rest the shift shows: the vertex sits 1 m along +x of where it is authored.
        expect_near(skin(c, s.value(), rest_model(s.value()), *m1, v), file_positions[v] + glm::vec3(1, 0, 0), 1e-5f);
    }
    EXPECT_FALSE(has_note(c, "disagree")) << "skin 1's joints agree on its offset: exact, no note";
}

// Weights (0.2, 0.2, 0, 0) become (0.5, 0.5, 0, 0) with one note for the file; normalised
// unsigned-byte weights summing to 255 are already exact (no note).
TEST(GltfWeights, UnnormalisedAreNormalisedWithOneNote) {
    for (bool bytes : {false, true}) {
        GltfBuilder b;
        const int j1 = b.node({{"name", "j1"}, {"translation", {0, 1, 0}}});
        const int j0 = b.node({{"name", "j0"}, {"children", {j1}}});
        const int weights = bytes ? b.accessor(std::vector<uint8_t>{128, 127, 0, 0, 255, 0, 0, 0, 55, 200, 0, 0}, "VEC4", 5121, true)
                                  : b.vec4({{0.2f, 0.2f, 0, 0}, {0.2f, 0.2f, 0, 0}, {1, 0, 0, 0}});
        const json prim = {{"attributes", {{"POSITION", b.vec3({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}})}, {"JOINTS_0", b.joints({0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0})}, {"WEIGHTS_0", weights}}}};
        b.root(j0);
        b.root(b.node({{"mesh", b.mesh(json::array({prim, prim}))}, {"skin", 0}}));
        b.skin({j0, j1}, {});
        Result<GltfCharacter> r = load(b);
        ASSERT_TRUE(r.ok()) << r.error().to_string();
        const GltfCharacter& c = r.value();
        ASSERT_EQ(c.meshes.size(), 2u);
        if (!bytes) {
            expect_near(glm::vec3(c.meshes[0].weights[0]), glm::vec3(0.5f, 0.5f, 0));
            EXPECT_TRUE(has_note(c, "4 vertices in 2 primitives had joint weights not summing to 1; normalised"))
                << (c.notes.empty() ? "" : c.notes[0]);
        } else {
            EXPECT_NEAR(c.meshes[0].weights[0][0], 128.0f / 255.0f, 1e-6f);
            EXPECT_FALSE(has_note(c, "not summing to 1"));
        }
        size_t weight_notes = 0;
        for (const std::string& n : c.notes) weight_notes += n.find("weights") != std::string::npos;
        EXPECT_LE(weight_notes, 1u);
    }
}

// Eight influences (JOINTS_1/WEIGHTS_1): the 4 largest are kept and renormalised.
TEST(GltfWeights, EightInfluencesKeepTheLargestFour) {
    GltfBuilder b;
    std::vector<int> joints;
    for (int i = 0; i < 8; ++i) joints.push_back(b.node({{"name", "j" + std::to_string(i)}}));
    for (int j : joints) b.root(j);
    const json prim = {{"attributes",
                        {{"POSITION", b.vec3({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}})},
                         {"JOINTS_0", b.joints({0, 1, 2, 3, 0, 1, 2, 3, 0, 1, 2, 3})},
                         {"WEIGHTS_0", b.vec4({{0.05f, 0.3f, 0.05f, 0.05f}, {1, 0, 0, 0}, {1, 0, 0, 0}})},
                         {"JOINTS_1", b.joints({4, 5, 6, 7, 4, 5, 6, 7, 4, 5, 6, 7})},
                         {"WEIGHTS_1", b.vec4({{0.2f, 0.05f, 0.25f, 0.05f}, {0, 0, 0, 0}, {0, 0, 0, 0}})}}}};
    b.root(b.node({{"mesh", b.mesh(json::array({prim}))}, {"skin", 0}}));
    b.skin(joints, {});
    Result<GltfCharacter> r = load(b);
    ASSERT_TRUE(r.ok()) << r.error().to_string();
    const GltfCharacter& c = r.value();
    Result<Skeleton> s = build_skeleton(c.skeleton, "fixture");
    ASSERT_TRUE(s.ok());
    // Largest: j1 0.3, j6 0.25, j4 0.2, then the first 0.05 (j0); kept sum 0.8.
    const GltfSkinnedMesh& m = c.meshes[0];
    EXPECT_EQ(m.joints[0][0], s.value().find("j1"));
    EXPECT_EQ(m.joints[0][1], s.value().find("j6"));
    EXPECT_EQ(m.joints[0][2], s.value().find("j4"));
    EXPECT_NEAR(m.weights[0][0], 0.3f / 0.8f, 1e-6f);
    EXPECT_NEAR(m.weights[0][3], 0.05f / 0.8f, 1e-6f);
    EXPECT_TRUE(has_note(c, "JOINTS_1/WEIGHTS_1"));
}

// No NORMAL: flat normals (the spec's MUST): a folded quad (two triangles in different planes,
// sharing an edge) becomes 6 corners, each carrying its own triangle's face normal.
TEST(GltfNormals, MissingNormalsAreFlat) {
    GltfBuilder b;
    const int j = b.node({{"name", "j"}, {"mesh", 0}});
    b.root(j);
    // Triangle 0 in z = 0 (normal +z), triangle 1 from the shared edge (1,0,0)-(0,1,0) to (1,1,1).
    b.mesh(json::array({{{"attributes", {{"POSITION", b.vec3({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 1}})}}}, {"indices", b.indices({0, 1, 2, 2, 1, 3})}}}));
    b.skin({j}, {});
    Result<GltfCharacter> r = load(b);
    ASSERT_TRUE(r.ok()) << r.error().to_string();
    const GltfSkinnedMesh& m = r.value().meshes[0];
    ASSERT_EQ(m.positions.size(), 6u);
    ASSERT_EQ(m.indices, (std::vector<uint32_t>{0, 1, 2, 3, 4, 5}));
    for (size_t v = 0; v < 3; ++v) expect_near(m.normals[v], glm::vec3(0, 0, 1));
    // (1,0,0)-(0,1,0) = (-1,1,0)... face normal of (0,1,0),(1,0,0),(1,1,1): (1,-1,0) x (1,0,1) = (-1,-1,1)/sqrt3.
    const glm::vec3 n1 = glm::normalize(glm::vec3(-1, -1, 1));
    for (size_t v = 3; v < 6; ++v) expect_near(m.normals[v], n1);
    EXPECT_TRUE(has_note(r.value(), "1 primitive without NORMAL: flat normals computed"));
}

// Morph targets: with no default weights the base shape is kept; mesh.weights apply; node.weights
// override them; a `weights` animation channel is skipped with one note.
TEST(GltfMorphTargets, BaseShapeKeptOrDefaultWeightsApplied) {
    for (int variant = 0; variant < 3; ++variant) {
        GltfBuilder b;
        const int up = b.vec3({{0, 1, 0}, {0, 1, 0}, {0, 1, 0}});
        json prim = triangle(b)[0];
        prim["targets"] = json::array({{{"POSITION", up}}});
        const int mesh = b.mesh(json::array({prim}));
        if (variant >= 1) b.doc["meshes"][mesh]["weights"] = {0.5};
        json node = {{"name", "j"}, {"mesh", mesh}};
        if (variant == 2) node["weights"] = {0.25};
        const int j = b.node(node);
        b.root(j);
        b.skin({j}, {});
        const int times = b.scalars({0.0f, 1.0f});
        const int values = b.scalars({0.0f, 1.0f});
        b.doc["animations"] = json::array({{{"samplers", json::array({{{"input", times}, {"output", values}}})},
                                            {"channels", json::array({{{"sampler", 0}, {"target", {{"node", j}, {"path", "weights"}}}}})}}});
        Result<GltfCharacter> r = load(b);
        ASSERT_TRUE(r.ok()) << r.error().to_string();
        const float lift = variant == 0 ? 0.0f : variant == 1 ? 0.5f : 0.25f;
        expect_near(r.value().meshes[0].positions[1], glm::vec3(1, lift, 0));
        EXPECT_TRUE(has_note(r.value(), "1 primitive with morph targets"));
        EXPECT_TRUE(has_note(r.value(), "1 morph target weight channel skipped"));
    }
}

// Writes a w x h RGBA8 PNG into memory with stb_image_write.
std::vector<unsigned char> png(int w, int h, const std::vector<uint8_t>& rgba) { return test::png_bytes(rgba, w, h); }

// One mesh, three primitives: a red factor material, a textured one (2x1 PNG, TEXCOORD_1, clamp)
// and none (default). Each primitive keeps its material, UVs come from the texCoord set named by
// the material, and the texture decodes to the PNG's pixels.
TEST(GltfMaterials, SeveralPrimitivesAndMaterials) {
    GltfBuilder b;
    const int image = b.image(png(2, 1, {255, 0, 0, 255, 0, 0, 255, 255}));
    b.doc["samplers"] = json::array({{{"wrapS", 33071}, {"wrapT", 33648}, {"magFilter", 9728}}});
    b.doc["textures"] = json::array({{{"source", image}, {"sampler", 0}}});
    b.doc["materials"] = json::array({{{"name", "red"}, {"pbrMetallicRoughness", {{"baseColorFactor", {1, 0, 0, 1}}}}},
                                      {{"name", "cloth"}, {"pbrMetallicRoughness", {{"baseColorFactor", {0.5, 0.5, 0.5, 1}}, {"baseColorTexture", {{"index", 0}, {"texCoord", 1}}}}}}});
    json p0 = triangle(b)[0], p1 = triangle(b)[0], p2 = triangle(b)[0];
    p0["material"] = 0;
    p1["material"] = 1;
    p1["attributes"]["TEXCOORD_0"] = b.vec2({{9, 9}, {9, 9}, {9, 9}});
    p1["attributes"]["TEXCOORD_1"] = b.vec2({{0, 0}, {1, 0}, {0.25f, 1}});
    const int j = b.node({{"name", "j.L"}, {"mesh", b.mesh(json::array({p0, p1, p2}))}});
    b.root(j);
    b.skin({j}, {});
    Result<GltfCharacter> r = load(b);
    ASSERT_TRUE(r.ok()) << r.error().to_string();
    const GltfCharacter& c = r.value();
    ASSERT_EQ(c.meshes.size(), 3u);
    EXPECT_EQ(c.meshes[0].material, 0);
    EXPECT_EQ(c.meshes[1].material, 1);
    EXPECT_EQ(c.meshes[2].material, -1);
    EXPECT_TRUE(c.meshes[0].uvs.empty());
    ASSERT_EQ(c.meshes[1].uvs.size(), 3u);
    EXPECT_EQ(c.meshes[1].uvs[2], glm::vec2(0.25f, 1));
    ASSERT_EQ(c.materials.size(), 2u);
    EXPECT_EQ(c.materials[0].base_colour, glm::vec4(1, 0, 0, 1));
    EXPECT_EQ(c.materials[1].texture, 0);
    ASSERT_EQ(c.textures.size(), 1u);
    const TextureImage& t = c.textures[0];
    EXPECT_EQ(t.width, 2u);
    EXPECT_EQ(t.height, 1u);
    EXPECT_EQ(t.rgba, (std::vector<uint8_t>{255, 0, 0, 255, 0, 0, 255, 255}));
    EXPECT_EQ(t.wrap_u, TextureWrap::ClampToEdge);
    EXPECT_EQ(t.wrap_v, TextureWrap::MirroredRepeat);
    EXPECT_TRUE(t.nearest);
    EXPECT_EQ(c.skeleton.joints[0].name, "j.L") << "dotted names are kept";
}

// A textured material on a primitive without its TEXCOORD set, and an image that cannot be
// decoded: both drawn with the base colour only, with notes; the file still loads.
TEST(GltfMaterials, UnusableTexturesAreNoted) {
    GltfBuilder b;
    const int image = b.image({1, 2, 3, 4, 5, 6, 7, 8});
    const int good = b.image(png(1, 1, {1, 2, 3, 255}));
    b.doc["textures"] = json::array({{{"source", image}}, {{"source", good}}});
    b.doc["materials"] = json::array({{{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}}}}}},
                                      {{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 1}}}}}}});
    json p0 = triangle(b)[0], p1 = triangle(b)[0];
    p0["material"] = 0;
    p1["material"] = 1;  // no TEXCOORD_0
    const int j = b.node({{"name", "j"}, {"mesh", b.mesh(json::array({p0, p1}))}});
    b.root(j);
    b.skin({j}, {});
    Result<GltfCharacter> r = load(b);
    ASSERT_TRUE(r.ok()) << r.error().to_string();
    const GltfCharacter& c = r.value();
    EXPECT_EQ(c.materials[0].texture, -1);
    EXPECT_TRUE(has_note(c, "images[0]: not a PNG, JPEG or WebP image"));
    EXPECT_TRUE(has_note(c, "1 primitive using a textured material without its TEXCOORD set"));
    ASSERT_EQ(c.meshes.size(), 2u);
    EXPECT_EQ(c.materials[static_cast<size_t>(c.meshes[1].material)].texture, -1);
}

// alphaMode: MASK keeps its alphaCutoff (default 0.5), BLEND is alpha-tested at 0.5 with a note, OPAQUE
// and no mode draw every fragment; a cutoff above 1 is noted (nothing drawn), a negative one or an
// unknown mode is an error naming the material.
TEST(GltfMaterials, AlphaModes) {
    auto with = [](const json& materials) {
        GltfBuilder b;
        b.doc["materials"] = materials;
        json prims = json::array();
        for (size_t k = 0; k < materials.size(); ++k) {
            json p = triangle(b)[0];
            p["material"] = k;
            prims.push_back(p);
        }
        const int j = b.node({{"name", "j"}, {"mesh", b.mesh(prims)}});
        b.root(j);
        b.skin({j}, {});
        return load(b);
    };
    Result<GltfCharacter> r = with(json::array({{{"alphaMode", "MASK"}, {"alphaCutoff", 0.25}}, {{"alphaMode", "MASK"}},
                                                {{"alphaMode", "BLEND"}}, {{"alphaMode", "OPAQUE"}, {"alphaCutoff", 0.7}},
                                                json::object(), {{"alphaMode", "MASK"}, {"alphaCutoff", 2.0}}}));
    ASSERT_TRUE(r.ok()) << r.error().to_string();
    const std::vector<SurfaceMaterial>& m = r.value().materials;
    ASSERT_EQ(m.size(), 6u);
    EXPECT_EQ(m[0].alpha_cutoff, 0.25f);
    EXPECT_EQ(m[1].alpha_cutoff, 0.5f);
    EXPECT_EQ(m[2].alpha_cutoff, 0.5f);
    EXPECT_LT(m[3].alpha_cutoff, 0.0f);
    EXPECT_LT(m[4].alpha_cutoff, 0.0f);
    EXPECT_EQ(m[5].alpha_cutoff, 1.0f);
    EXPECT_TRUE(has_note(r.value(), "materials[2]: alphaMode BLEND is drawn alpha-tested at 0.5"));
    EXPECT_TRUE(has_note(r.value(), "materials[5]: alphaCutoff above 1: no fragment of the material is drawn"));
    for (const std::string& n : r.value().notes) EXPECT_EQ(n.find("drawn opaque"), std::string::npos) << n;

    Result<GltfCharacter> negative = with(json::array({{{"alphaMode", "MASK"}, {"alphaCutoff", -0.1}}}));
    ASSERT_FALSE(negative.ok());
    EXPECT_EQ(negative.error().path, "materials[0].alphaCutoff");
    Result<GltfCharacter> unknown = with(json::array({{{"alphaMode", "CUTOUT"}}}));
    ASSERT_FALSE(unknown.ok());
    EXPECT_EQ(unknown.error().path, "materials[0].alphaMode");
    EXPECT_NE(unknown.error().message.find("'CUTOUT' is none of OPAQUE, MASK, BLEND"), std::string::npos) << unknown.error().to_string();
}

// KHR_materials_unlit: the material is drawn without lighting; a file requiring the extension loads.
TEST(GltfMaterials, UnlitMaterials) {
    GltfBuilder b;
    b.doc["extensionsUsed"] = {"KHR_materials_unlit"};
    b.doc["extensionsRequired"] = {"KHR_materials_unlit"};
    b.doc["materials"] = json::array({{{"extensions", {{"KHR_materials_unlit", json::object()}}}}, json::object()});
    json p0 = triangle(b)[0], p1 = triangle(b)[0];
    p0["material"] = 0;
    p1["material"] = 1;
    const int j = b.node({{"name", "j"}, {"mesh", b.mesh(json::array({p0, p1}))}});
    b.root(j);
    b.skin({j}, {});
    Result<GltfCharacter> r = load(b);
    ASSERT_TRUE(r.ok()) << r.error().to_string();
    ASSERT_EQ(r.value().materials.size(), 2u);
    EXPECT_TRUE(r.value().materials[0].unlit);
    EXPECT_FALSE(r.value().materials[1].unlit);
    EXPECT_TRUE(has_note(r.value(), "KHR_materials_unlit: 1 material drawn without lighting"));
}

// Duplicate, dotted and prefixed names: kept as they are, a repeated name made unique with a note.
TEST(GltfNames, DuplicateAndDottedNames) {
    GltfBuilder b;
    const int c2 = b.node({{"name", "mixamorig:Spine"}});
    const int c1 = b.node({{"name", "thigh.L"}, {"children", {c2}}});
    const int c0 = b.node({{"name", "thigh.L"}, {"children", {c1}}});
    b.root(c0);
    b.skin({c0, c1, c2}, {});
    Result<GltfCharacter> r = load(b);
    ASSERT_TRUE(r.ok()) << r.error().to_string();
    Result<Skeleton> s = build_skeleton(r.value().skeleton, "fixture");
    ASSERT_TRUE(s.ok());
    EXPECT_GE(s.value().find("thigh.L"), 0);
    EXPECT_GE(s.value().find("thigh.L_node1"), 0);
    EXPECT_GE(s.value().find("mixamorig:Spine"), 0);
    EXPECT_TRUE(has_note(r.value(), "duplicate joint name 'thigh.L' renamed to 'thigh.L_node1'"));
}

// Triangle strips and fans become lists in the spec's vertex order; lines are left out with a note.
TEST(GltfPrimitives, StripsFansAndLines) {
    GltfBuilder b;
    const int pos = b.vec3({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}});
    const int normal = b.vec3({{0, 0, 1}, {0, 0, 1}, {0, 0, 1}, {0, 0, 1}});
    const json strip = {{"attributes", {{"POSITION", pos}, {"NORMAL", normal}}}, {"mode", 5}};
    const json fan = {{"attributes", {{"POSITION", pos}, {"NORMAL", normal}}}, {"mode", 6}};
    const json lines = {{"attributes", {{"POSITION", pos}}}, {"mode", 1}};
    const int j = b.node({{"name", "j"}, {"mesh", b.mesh(json::array({strip, fan, lines}))}});
    b.root(j);
    b.skin({j}, {});
    Result<GltfCharacter> r = load(b);
    ASSERT_TRUE(r.ok()) << r.error().to_string();
    ASSERT_EQ(r.value().meshes.size(), 2u);
    EXPECT_EQ(r.value().meshes[0].indices, (std::vector<uint32_t>{0, 1, 2, 1, 3, 2}));  // spec: {v_i, v_i+1+i%2, v_i+2-i%2}
    EXPECT_EQ(r.value().meshes[1].indices, (std::vector<uint32_t>{1, 2, 0, 2, 3, 0}));
    EXPECT_TRUE(has_note(r.value(), "1 point or line primitive left out"));
}

}  // namespace
}  // namespace aloha
