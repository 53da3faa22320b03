// The humanoid map: one test per naming convention (project-written skeletons with the built-in
// humanoid's proportions, renamed), each mapping every canonical joint the convention has and
// nothing else; the explicit humanoid_map; its errors.
#include "engine/anim/humanoid_map.hpp"
#include "tests/common/rig_fixtures.hpp"

#include <gtest/gtest.h>

namespace aloha {
namespace {

using test::ExtraJoint;
using test::sided;

// Maps the renamed humanoid and checks: the convention, humanoid, every table entry mapped to its
// file joint, every canonical joint left out of the table unmapped, the extras ignored.
void expect_maps(const std::map<std::string, std::string>& names, const std::string& convention,
                 const std::vector<ExtraJoint>& extras = {}) {
    const Skeleton sk = build_skeleton(test::renamed_humanoid(names, extras), "fixture").value();
    auto map = map_humanoid(sk);
    ASSERT_TRUE(map.ok()) << map.error().to_string();
    EXPECT_EQ(map.value().convention, convention);
    EXPECT_TRUE(map.value().humanoid);
    for (const CanonicalJoint& c : canonical_humanoid()) {
        const auto it = names.find(c.name);
        const int expected = it == names.end() ? -1 : sk.find(it->second);
        EXPECT_EQ(map.value().find(c.name), expected) << convention << ": canonical " << c.name;
    }
    const std::vector<std::string> ignored = unmapped_joints(sk, map.value());
    EXPECT_EQ(ignored.size(), extras.size()) << convention;
    for (const ExtraJoint& e : extras) EXPECT_NE(std::find(ignored.begin(), ignored.end(), e.name), ignored.end()) << e.name;
}

TEST(HumanoidMap, CanonicalJointsAreTheBuiltInHumanoid) {
    const Skeleton h = test::humanoid_skeleton_for();
    ASSERT_EQ(h.joint_count(), static_cast<int>(canonical_humanoid().size()));
    for (const CanonicalJoint& c : canonical_humanoid()) {
        const int j = h.find(c.name);
        ASSERT_GE(j, 0) << c.name;
        const int p = h.parents()[static_cast<size_t>(j)];
        EXPECT_EQ(p < 0 ? std::string() : h.names()[static_cast<size_t>(p)],
                  c.parent < 0 ? std::string() : canonical_humanoid()[static_cast<size_t>(c.parent)].name) << c.name;
    }
}

TEST(HumanoidMap, CmuBvh) {
    std::map<std::string, std::string> names;
    for (const CanonicalJoint& c : canonical_humanoid()) names[c.name] = c.name;
    expect_maps(names, "CMU BVH", {{"LeftToe_End", "LeftToe", {0, 0, 0.05f}}});
}

TEST(HumanoidMap, MixamoWithNamespace) {
    const auto names = test::mixamo_names();
    // Mixamo's LeftShoulder is the collar bone, unlike CMU's: the whole convention decides.
    expect_maps(names, "Mixamo / HumanIK",
                {{"mixamorig:HeadTop_End", "mixamorig:Head", {0, 0.12f, 0}}, {"mixamorig:LeftHandIndex1", "mixamorig:LeftHand", {0, -0.05f, 0.01f}}});
}

TEST(HumanoidMap, UnityHumanoid) {
    const auto names = test::unity_humanoid_names();
    expect_maps(names, "Unity Humanoid / VRM", {{"LeftEye", "Head", {0.03f, 0.08f, 0.08f}}});
}

TEST(HumanoidMap, VrmBoneNames) {
    const auto names = test::vrm_names();
    expect_maps(names, "Unity Humanoid / VRM");
}

TEST(HumanoidMap, VroidNodeNames) {
    const auto names = test::vroid_names();
    expect_maps(names, "VRoid", {{"J_Sec_Hair1_01", "J_Bip_C_Head", {0, 0.1f, -0.05f}}});
}

TEST(HumanoidMap, UnrealMannequin) {
    const auto names = test::unreal_names();
    // Twist and IK helper bones are carried along and ignored.
    expect_maps(names, "Unreal mannequin",
                {{"thigh_twist_01_l", "thigh_l", {0, -0.2f, 0}}, {"ik_foot_l", "pelvis", {0.1f, -0.9f, 0}}});
}

TEST(HumanoidMap, PoserBvh) {
    auto names = test::poser_names();
    names["LFingers"] = "lMid1";
    names["RFingers"] = "rMid1";
    names["LThumb"] = "lThumb1";
    names["RThumb"] = "rThumb1";
    expect_maps(names, "Poser / DAZ", {{"lIndex1", "lHand", {0.01f, -0.09f, 0.02f}}, {"lButtock", "hip", {0.06f, -0.08f, -0.08f}}});
}

TEST(HumanoidMap, DazGenesis) {
    const auto names = test::daz_names();
    expect_maps(names, "Poser / DAZ", {{"lThighTwist", "lThighBend", {0, -0.2f, 0}}});
}

TEST(HumanoidMap, BlenderRigifyWithDefPrefix) {
    const auto names = test::rigify_names("DEF-");
    // "thigh.L.001" is a twist segment of the thigh, not the thigh.
    expect_maps(names, "Blender Rigify", {{"DEF-thigh.L.001", "DEF-thigh.L", {0, -0.2f, 0}}});
}

TEST(HumanoidMap, BlenderSuffixAndPrefixSides) {
    for (const auto& [left, right] : {std::pair<std::string, std::string>{".L", ".R"}, {"_L", "_R"}, {"_l", "_r"}}) {
        auto names = test::unity_names(left, right, false);
        expect_maps(names, "Unity Humanoid / VRM");
    }
    auto prefixed = sided({{"Hips", "Hips"}, {"lowerback", "Spine"}, {"Head", "Head"}},
                          {{"LeftHip", "%_UpperLeg"}, {"LeftKnee", "%_LowerLeg"}, {"LeftAnkle", "%_Foot"},
                           {"LeftShoulder", "%_UpperArm"}, {"LeftElbow", "%_LowerArm"}, {"LeftWrist", "%_Hand"}},
                          "L", "R");
    expect_maps(prefixed, "Unity Humanoid / VRM");
}

TEST(HumanoidMap, ExplicitMapCompletesAnUnknownRig) {
    // CesiumMan-like names no convention knows.
    const auto names = test::odd_names();
    const Skeleton sk = build_skeleton(test::renamed_humanoid(names), "fixture").value();
    auto bare = map_humanoid(sk);
    ASSERT_TRUE(bare.ok());
    EXPECT_FALSE(bare.value().humanoid);
    EXPECT_FALSE(bare.value().missing.empty());
    auto map = map_humanoid(sk, names, "scene.json", "/character_types/0/humanoid_map");
    ASSERT_TRUE(map.ok()) << map.error().to_string();
    EXPECT_TRUE(map.value().humanoid);
    EXPECT_EQ(map.value().find("LeftKnee"), sk.find("leg_L_2"));
    EXPECT_TRUE(map.value().from_explicit[static_cast<size_t>(canonical_index("LeftKnee"))]);
    EXPECT_EQ(find_joint(sk, map.value(), "RightWrist"), sk.find("arm_R_2"));  // canonical name
    EXPECT_EQ(find_joint(sk, map.value(), "arm_R_2"), sk.find("arm_R_2"));     // the file's own name
    // A missing optional joint folds onto its nearest mapped canonical ancestor.
    EXPECT_EQ(map.value().fold(canonical_index("LHipJoint")), sk.find("torso_1"));
}

TEST(HumanoidMap, ExplicitMapErrorsNameTheSceneAndPointer) {
    std::map<std::string, std::string> names;
    for (const CanonicalJoint& c : canonical_humanoid()) names[c.name] = c.name;
    const Skeleton sk = build_skeleton(test::renamed_humanoid(names), "fixture").value();
    auto unknown = map_humanoid(sk, {{"LeftFemur", "LeftHip"}}, "scene.json", "/character_types/2/humanoid_map");
    ASSERT_FALSE(unknown.ok());
    EXPECT_EQ(unknown.error().to_string(),
              "scene.json: /character_types/2/humanoid_map/LeftFemur: 'LeftFemur' is not a canonical humanoid joint (see docs/CHARACTERS.md)");
    auto absent = map_humanoid(sk, {{"LeftKnee", "knee_l"}}, "scene.json", "/t/humanoid_map");
    ASSERT_FALSE(absent.ok());
    EXPECT_EQ(absent.error().path, "/t/humanoid_map/LeftKnee");
    EXPECT_NE(absent.error().message.find("'knee_l' is not in the skeleton"), std::string::npos);
    auto twice = map_humanoid(sk, {{"LeftKnee", "LeftHip"}, {"LeftAnkle", "LeftHip"}}, "scene.json", "/t/humanoid_map");
    ASSERT_FALSE(twice.ok());
    EXPECT_NE(twice.error().message.find("already given for"), std::string::npos);
}

TEST(HumanoidMap, DeclaredMapMapsNamesNoConventionReads) {
    // A VRM file's humanoid declaration over joints named "Bone.000"...: the declaration alone maps it.
    const auto names = test::numbered_names();
    const Skeleton sk = build_skeleton(test::renamed_humanoid(names), "fixture").value();
    ASSERT_FALSE(map_humanoid(sk).value().humanoid);
    auto map = map_humanoid(sk, {}, "", "", DeclaredHumanoid{"VRM 1.0 humanoid", names});
    ASSERT_TRUE(map.ok()) << map.error().to_string();
    EXPECT_TRUE(map.value().humanoid);
    EXPECT_EQ(map.value().convention, "VRM 1.0 humanoid");
    for (const CanonicalJoint& c : canonical_humanoid()) {
        const auto it = names.find(c.name);
        EXPECT_EQ(map.value().find(c.name), it == names.end() ? -1 : sk.find(it->second)) << c.name;
        EXPECT_EQ(map.value().from_declared[static_cast<size_t>(canonical_index(c.name))], it != names.end()) << c.name;
    }
}

TEST(HumanoidMap, DeclaredMapOverridesConventionsAndTheSceneOverridesIt) {
    // Mixamo names the convention reads whole; the file declares the left knee elsewhere (a twist
    // joint it added), which the convention's guess gives up; the scene's humanoid_map wins over both.
    const auto names = test::mixamo_names();
    RawSkeleton raw = test::renamed_humanoid(names);
    test::insert_between(raw, "mixamorig:LeftFoot", "LeftKneeTwist", 0.2f);
    const Skeleton sk = build_skeleton(raw, "fixture").value();
    const DeclaredHumanoid declared{"VRM 0.x humanoid", {{"LeftKnee", "LeftKneeTwist"}, {"LeftAnkle", "mixamorig:LeftLeg"}}};
    auto map = map_humanoid(sk, {}, "", "", declared);
    ASSERT_TRUE(map.ok()) << map.error().to_string();
    EXPECT_EQ(map.value().convention, "VRM 0.x humanoid + Mixamo / HumanIK names");
    EXPECT_EQ(map.value().find("LeftKnee"), sk.find("LeftKneeTwist"));
    EXPECT_EQ(map.value().find("LeftAnkle"), sk.find("mixamorig:LeftLeg"));  // taken from the convention's LeftKnee
    EXPECT_EQ(map.value().canonical_of(sk.find("mixamorig:LeftFoot")), -1);   // the convention's LeftAnkle, given up
    EXPECT_EQ(map.value().find("RightKnee"), sk.find("mixamorig:RightLeg"));  // the convention fills the rest
    auto scene = map_humanoid(sk, {{"LeftAnkle", "mixamorig:LeftFoot"}, {"LeftKnee", "mixamorig:LeftLeg"}}, "s.json", "/m", declared);
    ASSERT_TRUE(scene.ok()) << scene.error().to_string();
    EXPECT_EQ(scene.value().convention, "VRM 0.x humanoid + Mixamo / HumanIK names + humanoid_map");
    const auto knee = static_cast<size_t>(canonical_index("LeftKnee"));
    EXPECT_EQ(scene.value().find("LeftKnee"), sk.find("mixamorig:LeftLeg"));
    EXPECT_EQ(scene.value().find("LeftAnkle"), sk.find("mixamorig:LeftFoot"));
    EXPECT_TRUE(scene.value().from_explicit[knee]);
    EXPECT_FALSE(scene.value().from_declared[knee]);
    EXPECT_EQ(scene.value().canonical_of(sk.find("LeftKneeTwist")), -1);
}

TEST(HumanoidMap, HumanoidBoneNamesOfUnityAndVrm) {
    const std::pair<const char*, const char*> bones[] = {
        {"hips", "Hips"}, {"spine", "lowerback"}, {"chest", "Chest"}, {"upperChest", "Chest2"}, {"neck", "lowerneck"},
        {"head", "Head"}, {"leftUpperLeg", "LeftHip"}, {"rightLowerLeg", "RightKnee"}, {"leftFoot", "LeftAnkle"},
        {"rightToes", "RightToe"}, {"leftShoulder", "LeftCollar"}, {"rightUpperArm", "RightShoulder"},
        {"leftLowerArm", "LeftElbow"}, {"RightHand", "RightWrist"}, {"leftMiddleProximal", "LFingers"},
        {"leftEye", ""}, {"jaw", ""}, {"leftIndexProximal", ""}, {"rightThumbDistal", ""}, {"tail", ""}, {"left", ""}};
    for (const auto& [bone, canonical] : bones) {
        EXPECT_EQ(canonical_of_humanoid_bone(bone, false), canonical) << bone;
        EXPECT_EQ(canonical_of_humanoid_bone(bone, true), canonical) << bone;
    }
    // The thumb's first bone: thumbProximal in VRM 0.x and Unity, thumbMetacarpal in VRM 1.0.
    EXPECT_EQ(canonical_of_humanoid_bone("leftThumbProximal", false), "LThumb");
    EXPECT_EQ(canonical_of_humanoid_bone("rightThumbMetacarpal", true), "RThumb");
    EXPECT_EQ(canonical_of_humanoid_bone("leftThumbProximal", true), "");
    EXPECT_EQ(canonical_of_humanoid_bone("leftThumbIntermediate", false), "");
}

TEST(HumanoidMap, NamesAreMatchedWithoutCaseOrSeparators) {
    EXPECT_EQ(joint_name_key("mixamorig:Left_Up.Leg"), "leftupleg");
    EXPECT_EQ(joint_name_key("Armature|DEF-thigh.L"), "thighl");
    std::map<std::string, std::string> names;
    for (const CanonicalJoint& c : canonical_humanoid()) names[c.name] = c.name;
    names["LeftKnee"] = "left_knee";
    names["RightKnee"] = "RIGHT-KNEE";
    expect_maps(names, "CMU BVH");
}

TEST(HumanoidMap, AQuadrupedIsNotAHumanoid) {
    RawSkeleton raw;
    auto add = [&](const char* name, int parent, glm::vec3 t) {
        raw.joints.push_back(RawJoint{name, parent, t});
        return static_cast<int>(raw.joints.size()) - 1;
    };
    const int pelvis = add("pelvis", -1, {0, 0.6f, -0.4f});
    const int chest = add("spine", pelvis, {0, 0.05f, 0.8f});
    add("head", chest, {0, 0.2f, 0.25f});
    for (const char* s : {"l", "r"}) {
        const float x = s[0] == 'l' ? 0.12f : -0.12f;
        add((std::string("back_leg_") + s).c_str(), pelvis, {x, -0.3f, 0});
        add((std::string("front_leg_") + s).c_str(), chest, {x, -0.35f, 0});
    }
    add("tail", pelvis, {0, 0.05f, -0.3f});
    const Skeleton sk = build_skeleton(raw, "dog").value();
    auto map = map_humanoid(sk);
    ASSERT_TRUE(map.ok());
    EXPECT_FALSE(map.value().humanoid);
    EXPECT_NE(std::find(map.value().missing.begin(), map.value().missing.end(), "LeftKnee"), map.value().missing.end());
}

}  // namespace
}  // namespace aloha
