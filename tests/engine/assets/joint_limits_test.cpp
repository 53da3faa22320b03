// Joint-limit table: the shipped humanoid file applied to the project's humanoid skeleton (CMU joint
// names, data/characters/humanoid.json), and bad inputs.
#include "engine/assets/humanoid_definition.hpp"
#include "engine/assets/joint_limits.hpp"

#include <gtest/gtest.h>

#include <glm/gtc/constants.hpp>

namespace aloha {
namespace {

const std::string kLimits = std::string(ALOHA_SOURCE_DIR) + "/data/characters/humanoid_limits.json";
const std::string kHumanoid = std::string(ALOHA_SOURCE_DIR) + "/data/characters/humanoid.json";
// Degrees -> radians in float: one rounding of a value below pi, < 1e-6.
constexpr float kRadTol = 1e-6f;

TEST(JointLimits, HumanoidFileAppliesToHumanoidSkeleton) {
    Result<JointLimitTable> table = load_joint_limits(kLimits);
    ASSERT_TRUE(table.ok()) << table.error().to_string();
    Result<HumanoidDefinition> def = load_humanoid_definition(kHumanoid);
    ASSERT_TRUE(def.ok()) << def.error().to_string();
    Result<Skeleton> sk = build_skeleton(humanoid_skeleton(def.value(), HumanoidBody{}), "humanoid.json");
    ASSERT_TRUE(sk.ok()) << sk.error().to_string();
    Skeleton& s = sk.value();
    const Status applied = apply_joint_limits(s, table.value());
    ASSERT_TRUE(applied.ok()) << applied.error().to_string();
    auto limit = [&](const char* name) { return s.limits()[static_cast<size_t>(s.find(name))]; };
    for (const char* knee : {"LeftKnee", "RightKnee"}) {  // bend one way: flexion is +X
        EXPECT_TRUE(limit(knee).limited);
        EXPECT_NEAR(limit(knee).min_angles.x, 0.0f, kRadTol);
        EXPECT_NEAR(limit(knee).max_angles.x, glm::radians(150.0f), kRadTol);
    }
    for (const char* elbow : {"LeftElbow", "RightElbow"}) {  // forearm forward is -X
        EXPECT_LE(limit(elbow).max_angles.x, 0.0f);
        EXPECT_LE(limit(elbow).min_angles.x, glm::radians(-120.0f));
    }
    for (const char* wide : {"LeftShoulder", "RightShoulder", "LeftHip", "RightHip"})
        EXPECT_GT(limit(wide).max_angles.x - limit(wide).min_angles.x, glm::radians(150.0f)) << wide;
    for (const char* spine : {"lowerback", "Chest", "Chest2"})
        for (int a = 0; a < 3; ++a) {
            EXPECT_LE(limit(spine).max_angles[a], glm::radians(45.0f)) << spine;
            EXPECT_GE(limit(spine).min_angles[a], glm::radians(-45.0f)) << spine;
        }
    EXPECT_FALSE(limit("Hips").limited) << "the root is free";
    // The CMU captured walk 131_01 keeps the knee's first (Z-Y-X order) X angle in [0, 136.2] degrees,
    // inside the +X flexion range: the sign convention matches motion capture in that convention.
    EXPECT_GE(limit("RightKnee").max_angles.x, glm::radians(136.2f));
}

void expect_error(const std::string& text, const std::string& path, const std::string& part, int line = 0) {
    Result<JointLimitTable> r = parse_joint_limits(text, "limits.json");
    ASSERT_FALSE(r.ok()) << text;
    EXPECT_EQ(r.error().file, "limits.json");
    EXPECT_EQ(r.error().path, path) << r.error().to_string();
    EXPECT_EQ(r.error().line, line) << r.error().to_string();
    EXPECT_NE(r.error().message.find(part), std::string::npos) << r.error().to_string();
}

TEST(JointLimits, BadInputs) {
    expect_error(R"({"joints": {"Knee": {"min": [10, 0, 0], "max": [5, 0, 0]}}})", "/joints/Knee", "min exceeds max on axis X");
    expect_error(R"({"joints": {"Knee": {"min": [0, "ten", 0], "max": [5, 0, 0]}}})", "/joints/Knee/min/1", "expected a finite number");
    expect_error(R"({"joints": {"Knee": {"min": [0, 0], "max": [5, 0, 0]}}})", "/joints/Knee/min", "expected [x, y, z]");
    expect_error(R"({"joints": {"Knee": {"max": [5, 0, 0]}}})", "/joints/Knee", "missing required key 'min'");
    expect_error(R"({"joints": {"Knee": {"min": [0, 0, 0], "max": [500, 0, 0]}}})", "/joints/Knee/max/0", "within [-180.0, 180.0], got 500");
    expect_error(R"({"joints": {"Knee": {"min": [0, 0, 0], "max": [5, 0, 0], "mx": 1}}})", "/joints/Knee/mx", "unknown key");
    expect_error(R"({"units": "grads", "joints": {}})", "/units", "degrees");
    expect_error(R"({"joint": {}})", "/joint", "unknown key");
    expect_error(R"([1, 2])", "/", "expected an object, got array");
    // Every problem of a file is reported in one error (the first, then "and N more").
    Result<JointLimitTable> two = parse_joint_limits(R"({"units": "grads", "joints": {"Knee": {"min": [1, 0, 0], "max": [0, 0, 0]}}})", "limits.json");
    ASSERT_FALSE(two.ok());
    EXPECT_NE(two.error().message.find("and 1 more"), std::string::npos) << two.error().to_string();
    EXPECT_NE(two.error().message.find("min exceeds max on axis X"), std::string::npos) << two.error().to_string();
    expect_error("{\n  \"joints\": {\n    \"Knee\": {\"min\": [0, 0, 0,]}\n  }\n}", "", "invalid JSON", 3);
}

TEST(JointLimits, UnknownJointIsNamedWhenApplied) {
    Result<JointLimitTable> t = parse_joint_limits(R"({"joints": {"Tail": {"min": [0, 0, 0], "max": [1, 1, 1]}}})", "limits.json");
    ASSERT_TRUE(t.ok()) << t.error().to_string();
    RawSkeleton raw;
    raw.joints = {{"root", -1, {}, {}, {1, 1, 1}}};
    Result<Skeleton> s = build_skeleton(raw, "t");
    ASSERT_TRUE(s.ok());
    const Status st = apply_joint_limits(s.value(), t.value());
    ASSERT_FALSE(st.ok());
    EXPECT_EQ(st.error().file, "limits.json");
    EXPECT_EQ(st.error().path, "/joints/Tail");
    EXPECT_NE(st.error().message.find("'Tail'"), std::string::npos);
    EXPECT_FALSE(s.value().limits()[0].limited);
}

TEST(JointLimits, RadiansUnits) {
    Result<JointLimitTable> t = parse_joint_limits(R"({"units": "radians", "joints": {"A": {"min": [-1, 0, 0], "max": [1, 0.5, 0]}}})", "l.json");
    ASSERT_TRUE(t.ok()) << t.error().to_string();
    EXPECT_FLOAT_EQ(t.value().limits[0].max_angles.y, 0.5f);
    EXPECT_FLOAT_EQ(t.value().limits[0].min_angles.x, -1.0f);
}

}  // namespace
}  // namespace aloha
