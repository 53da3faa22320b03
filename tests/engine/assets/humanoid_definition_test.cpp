// The project's humanoid definition: the shipped file builds a skeleton whose landmarks sit at the
// anthropometric table's heights for any body, build widens it, and bad files are refused with the
// file and the JSON path.
#include "engine/anim/skeleton.hpp"
#include "engine/assets/humanoid_definition.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

namespace aloha {
namespace {

const std::string kFile = std::string(ALOHA_SOURCE_DIR) + "/data/characters/humanoid.json";

// Rest model position of joint `name` (rest rotations are identity, so offsets add up).
glm::vec3 rest_position(const RawSkeleton& raw, const std::string& name) {
    for (size_t i = 0; i < raw.joints.size(); ++i)
        if (raw.joints[i].name == name) {
            glm::vec3 p(0.0f);
            for (int j = static_cast<int>(i); j >= 0; j = raw.joints[static_cast<size_t>(j)].parent)
                p += raw.joints[static_cast<size_t>(j)].translation;
            return p;
        }
    ADD_FAILURE() << "no joint " << name;
    return {};
}

TEST(HumanoidDefinition, LandmarksFollowTheAnthropometricTable) {
    auto def = load_humanoid_definition(kFile);
    ASSERT_TRUE(def.ok()) << def.error().to_string();
    EXPECT_FALSE(def.value().muscles.empty());
    EXPECT_FALSE(def.value().limits.empty());
    for (float h : {1.55f, 1.75f, 1.95f}) {
        const RawSkeleton raw = humanoid_skeleton(def.value(), HumanoidBody{h, 0.5f});
        auto sk = build_skeleton(raw, kFile);
        ASSERT_TRUE(sk.ok()) << sk.error().to_string();
        EXPECT_EQ(sk.value().joint_count(), 31);
        // Drillis & Contini: ankle 0.039H, knee 0.285H, hip 0.530H; tolerance: float rounding.
        EXPECT_NEAR(rest_position(raw, "LeftAnkle").y, 0.039f * h, 1e-5f);
        EXPECT_NEAR(rest_position(raw, "RightKnee").y, 0.285f * h, 1e-5f);
        EXPECT_NEAR(rest_position(raw, "LeftHip").y, 0.530f * h, 1e-5f);
        EXPECT_NEAR(glm::length(rest_position(raw, "LeftElbow") - rest_position(raw, "LeftShoulder")), 0.186f * h, 1e-5f);
        EXPECT_GT(rest_position(raw, "LeftHip").x, 0.0f) << "+X is the character's left";
        EXPECT_NEAR(rest_position(raw, "LeftHip").x, -rest_position(raw, "RightHip").x, 1e-6f) << "mirrored";
    }
    const float slim = rest_position(humanoid_skeleton(def.value(), {1.75f, 0.0f}), "LeftShoulder").x;
    const float heavy = rest_position(humanoid_skeleton(def.value(), {1.75f, 1.0f}), "LeftShoulder").x;
    EXPECT_GT(heavy, slim * 1.1f) << "build widens the shoulders";
}

TEST(HumanoidDefinition, BadFilesNameTheFileAndPlace) {
    const auto dir = std::filesystem::temp_directory_path() / "aloha_humanoid_def_test";
    std::filesystem::create_directories(dir);
    auto refused = [&](const std::string& text, const std::string& want) {
        const std::string path = (dir / "h.json").string();
        std::ofstream(path) << text;
        auto r = load_humanoid_definition(path);
        if (r.ok()) return ::testing::AssertionFailure() << "accepted: " << text;
        const std::string msg = r.error().to_string();
        if (msg.find("h.json") == std::string::npos || msg.find(want) == std::string::npos)
            return ::testing::AssertionFailure() << "message '" << msg << "' lacks '" << want << "'";
        return ::testing::AssertionSuccess();
    };
    const std::string head = R"({"format": "aloha-humanoid", "version": 1, "reference_height": 1.75, )";
    EXPECT_TRUE(refused(head + R"("joints": [{"name": "A", "offset": [0, 1, 0]}, {"name": "B", "parent": "Z", "offset": [0, 1, 0]}]})",
                        "/joints/1/parent"));
    EXPECT_TRUE(refused(head + R"("joints": [{"name": "A", "offset": [0, 1, 0]}, {"name": "A", "parent": "A", "offset": [0, 1, 0]}]})",
                        "duplicate joint name 'A'"));
    EXPECT_TRUE(refused(head + R"("joints": [{"name": "A", "offset": [0, 1]}]})", "/joints/0/offset"));
    EXPECT_TRUE(refused(head + R"("joints": [{"name": "A", "offset": [0, 1, 0], "colour": 3}]})", "unknown key 'colour'"));
    EXPECT_TRUE(refused(head + R"("muscles": "nowhere.json", "joints": [{"name": "A", "offset": [0, 1, 0]}]})", "/muscles"));
    EXPECT_TRUE(refused(R"({"format": "aloha-humanoid", "version": 1,)", "h.json:1:"));
    EXPECT_TRUE(refused(R"({"format": "bvh", "version": 1, "reference_height": 1.75, "joints": [{"name": "A", "offset": [0,1,0]}]})",
                        "aloha-humanoid"));
    std::filesystem::remove_all(dir);
    EXPECT_FALSE(validate_humanoid_body({3.0f, 0.5f}, "scene.json", "/character_types/0").ok());
    EXPECT_FALSE(validate_humanoid_body({1.7f, -0.1f}, "scene.json", "/character_types/0").ok());
    EXPECT_TRUE(validate_humanoid_body({1.7f, 0.3f}, "scene.json", "/character_types/0").ok());
}

}  // namespace
}  // namespace aloha
