// The humanoid a glTF file declares (VRM 1.0's VRMC_vrm and VRM 0.x's VRM extension): read into
// GltfCharacter::humanoid whatever the nodes are called, non-canonical and non-joint bones noted,
// malformed declarations refused naming their JSON path. Fixtures: the built-in humanoid's
// proportions with joints named "Bone.000"... (tests/common/rig_fixtures.hpp).
#include "engine/assets/gltf_loader.hpp"
#include "tests/common/rig_fixtures.hpp"

#include <gtest/gtest.h>

namespace aloha {
namespace {

struct Fixture {
    RawSkeleton raw;
    std::map<std::string, std::string> names;  // canonical -> "Bone.NNN"
    nlohmann::json gltf;
};

Fixture vrm_fixture(bool vrm1) {
    Fixture f;
    f.names = test::numbered_names();
    f.raw = test::renamed_humanoid(f.names);
    f.gltf = nlohmann::json::parse(test::gltf_text(f.raw, 1, 0.3f));
    test::add_vrm_humanoid(f.gltf, f.raw, f.names, vrm1);
    return f;
}

Result<GltfCharacter> parse(const nlohmann::json& j) { return parse_gltf_character(j.dump(), "vrm.gltf"); }

bool has_note(const GltfCharacter& g, const std::string& text) {
    for (const std::string& n : g.notes)
        if (n.find(text) != std::string::npos) return true;
    return false;
}

TEST(GltfHumanoid, Vrm1DeclarationNamesEveryCanonicalBone) {
    const Fixture f = vrm_fixture(true);
    auto g = parse(f.gltf);
    ASSERT_TRUE(g.ok()) << g.error().to_string();
    EXPECT_EQ(g.value().humanoid.origin, "VRM 1.0 humanoid");
    // Every declared bone that is a canonical joint comes back under its canonical name, the thumb
    // through VRM 1.0's thumbMetacarpal.
    EXPECT_EQ(g.value().humanoid.joints, f.names);
    EXPECT_TRUE(has_note(g.value(), "VRM 1.0 humanoid: " + std::to_string(f.names.size()) + " bones declared"));
}

TEST(GltfHumanoid, Vrm0DeclarationIsTheArrayForm) {
    const Fixture f = vrm_fixture(false);
    auto g = parse(f.gltf);
    ASSERT_TRUE(g.ok()) << g.error().to_string();
    EXPECT_EQ(g.value().humanoid.origin, "VRM 0.x humanoid");
    EXPECT_EQ(g.value().humanoid.joints, f.names);
}

TEST(GltfHumanoid, FilesWithoutVrmDeclareNothing) {
    const Fixture f = vrm_fixture(true);
    nlohmann::json j = f.gltf;
    j.erase("extensions");
    j.erase("extensionsUsed");
    auto g = parse(j);
    ASSERT_TRUE(g.ok()) << g.error().to_string();
    EXPECT_TRUE(g.value().humanoid.joints.empty());
    EXPECT_TRUE(g.value().humanoid.origin.empty());
}

TEST(GltfHumanoid, BonesTheLayersDoNotUseAreNotedNotMapped) {
    Fixture f = vrm_fixture(true);
    // A finger and an eye bone (not canonical joints) on nodes of their own.
    f.gltf["nodes"].push_back({{"name", "finger"}});
    f.gltf["extensions"]["VRMC_vrm"]["humanoid"]["humanBones"]["leftIndexProximal"] = {{"node", f.gltf["nodes"].size() - 1}};
    f.gltf["nodes"].push_back({{"name", "eye"}});
    f.gltf["extensions"]["VRMC_vrm"]["humanoid"]["humanBones"]["leftEye"] = {{"node", f.gltf["nodes"].size() - 1}};
    // A canonical bone on a node that is not a joint: left to the naming conventions.
    f.gltf["nodes"].push_back({{"name", "helper"}});
    const size_t spine_node = f.gltf["nodes"].size() - 1;
    f.gltf["extensions"]["VRMC_vrm"]["humanoid"]["humanBones"]["spine"] = {{"node", spine_node}};
    auto g = parse(f.gltf);
    ASSERT_TRUE(g.ok()) << g.error().to_string();
    EXPECT_EQ(g.value().humanoid.joints.count("lowerback"), 0u);
    EXPECT_EQ(g.value().humanoid.joints.at("Hips"), f.names.at("Hips"));
    EXPECT_TRUE(has_note(g.value(), "not canonical, carried along: leftEye, leftIndexProximal"));
    EXPECT_TRUE(has_note(g.value(), "no skin's joints, left to the naming conventions: spine (nodes[" + std::to_string(spine_node) + "])"));
    // "node": -1, as Unity-based exporters write a bone the avatar lacks: ignored with a note, not an error.
    f.gltf["extensions"]["VRMC_vrm"]["humanoid"]["humanBones"]["jaw"] = {{"node", -1}};
    auto unassigned = parse(f.gltf);
    ASSERT_TRUE(unassigned.ok()) << unassigned.error().to_string();
    EXPECT_TRUE(has_note(unassigned.value(), "bones declared without a node (-1), ignored: jaw"));
}

// Each malformed declaration: the error names the file and the JSON path and says what is wrong.
TEST(GltfHumanoid, MalformedDeclarationsAreRefusedNamingThePath) {
    struct Case {
        const char* what;
        bool vrm1;
        void (*edit)(nlohmann::json&);
        const char* path;
        const char* message;
    };
    const Case cases[] = {
        {"no humanoid", true, [](nlohmann::json& j) { j["extensions"]["VRMC_vrm"].erase("humanoid"); }, "extensions.VRMC_vrm",
         "has no humanoid.humanBones"},
        {"bones not an object", true, [](nlohmann::json& j) { j["extensions"]["VRMC_vrm"]["humanoid"]["humanBones"] = {1, 2}; },
         "extensions.VRMC_vrm.humanoid.humanBones", "expected an object of bone name"},
        {"entry without node", true, [](nlohmann::json& j) { j["extensions"]["VRMC_vrm"]["humanoid"]["humanBones"]["hips"] = {{"index", 0}}; },
         "extensions.VRMC_vrm.humanoid.humanBones.hips", "expected an object with a 'node' index"},
        {"node out of range", true, [](nlohmann::json& j) { j["extensions"]["VRMC_vrm"]["humanoid"]["humanBones"]["hips"]["node"] = 9999; },
         "extensions.VRMC_vrm.humanoid.humanBones.hips.node", "bone 'hips': expected a node index 0-"},
        {"negative node", true, [](nlohmann::json& j) { j["extensions"]["VRMC_vrm"]["humanoid"]["humanBones"]["hips"]["node"] = -2; },
         "extensions.VRMC_vrm.humanoid.humanBones.hips.node", "expected a node index"},
        {"fractional node", true, [](nlohmann::json& j) { j["extensions"]["VRMC_vrm"]["humanoid"]["humanBones"]["hips"]["node"] = 1.5; },
         "extensions.VRMC_vrm.humanoid.humanBones.hips.node", "expected a node index"},
        {"one node two bones", true, [](nlohmann::json& j) { j["extensions"]["VRMC_vrm"]["humanoid"]["humanBones"]["jaw"] = {{"node", 0}}; },
         "extensions.VRMC_vrm.humanoid.humanBones.jaw.node", "is declared for both"},
        {"VRM 0.x bones not an array", false, [](nlohmann::json& j) { j["extensions"]["VRM"]["humanoid"]["humanBones"] = "hips"; },
         "extensions.VRM.humanoid.humanBones", "expected an array"},
        {"VRM 0.x entry without bone", false, [](nlohmann::json& j) { j["extensions"]["VRM"]["humanoid"]["humanBones"][2].erase("bone"); },
         "extensions.VRM.humanoid.humanBones[2]", "expected an object with a 'bone' name"},
        {"VRM 0.x bone twice", false,
         [](nlohmann::json& j) {
             nlohmann::json& bones = j["extensions"]["VRM"]["humanoid"]["humanBones"];
             bones[1]["bone"] = bones[0]["bone"];
         },
         "extensions.VRM.humanoid.humanBones[1].node", "is declared twice"},
    };
    for (const Case& c : cases) {
        Fixture f = vrm_fixture(c.vrm1);
        c.edit(f.gltf);
        auto g = parse(f.gltf);
        ASSERT_FALSE(g.ok()) << c.what;
        EXPECT_EQ(g.error().file, "vrm.gltf") << c.what;
        EXPECT_EQ(g.error().path, c.path) << c.what << ": " << g.error().to_string();
        EXPECT_NE(g.error().message.find(c.message), std::string::npos) << c.what << ": " << g.error().to_string();
    }
}

}  // namespace
}  // namespace aloha
