// BVH loader on the CMU motion-capture file 131_01.bvh (a shared test asset, not in the repository;
// tests/common/test_assets.hpp; the BvhCmu tests skip without it) and on small hand-written files.
#include "engine/anim/skeleton.hpp"
#include "engine/assets/bvh_loader.hpp"
#include "tests/common/test_assets.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

namespace aloha {
namespace {

constexpr float kScale = 0.056444f;  // CMU unit in metres (BvhOptions default)

// float has a 24-bit mantissa: relative error of one rounding is 2^-24 ~ 6e-8; values here are
// products of at most a few roundings of numbers below 3 m, so 1e-6 m is a safe bound.
constexpr float kFloatTol = 1e-6f;

// The file at `path`, loaded once per test binary.
const BvhData& load_cmu(const std::string& path) {
    static const BvhData data = [&] {
        Result<BvhData> r = load_bvh(path);
        EXPECT_TRUE(r.ok()) << r.error().to_string();
        return r.ok() ? std::move(r).value() : BvhData{};
    }();
    return data;
}

// Every BvhCmu test needs 131_01.bvh: SetUp skips the test when it is absent.
class BvhCmu : public ::testing::Test {
protected:
    void SetUp() override {
        ALOHA_REQUIRE_TEST_ASSET(path, "131_01.bvh");
        file_ = path;
    }
    const BvhData& cmu() const { return load_cmu(file_); }
    std::string file_;
};

int find_raw(const RawSkeleton& s, const std::string& name) {
    for (size_t i = 0; i < s.joints.size(); ++i)
        if (s.joints[i].name == name) return static_cast<int>(i);
    return -1;
}

TEST_F(BvhCmu, JointsNamesAndRoot) {
    const BvhData& d = cmu();
    const std::vector<std::string> expected = {
        "Hips", "LHipJoint", "LeftHip", "LeftKnee", "LeftAnkle", "LeftToe", "RHipJoint", "RightHip",
        "RightKnee", "RightAnkle", "RightToe", "lowerback", "Chest", "Chest2", "lowerneck", "Neck", "Head",
        "LeftCollar", "LeftShoulder", "LeftElbow", "LeftWrist", "lhand", "LFingers", "LThumb", "RightCollar",
        "RightShoulder", "RightElbow", "RightWrist", "rhand", "RFingers", "RThumb"};
    ASSERT_EQ(d.skeleton.joints.size(), 31u);
    for (size_t i = 0; i < expected.size(); ++i) EXPECT_EQ(d.skeleton.joints[i].name, expected[i]) << i;
    EXPECT_EQ(d.skeleton.joints[0].parent, -1);
    for (size_t i = 1; i < 31; ++i) EXPECT_GE(d.skeleton.joints[i].parent, 0) << "only Hips is a root";
    EXPECT_EQ(d.skeleton.joints[static_cast<size_t>(find_raw(d.skeleton, "LeftKnee"))].parent, find_raw(d.skeleton, "LeftHip"));
    EXPECT_EQ(d.skeleton.joints[static_cast<size_t>(find_raw(d.skeleton, "LHipJoint"))].translation, glm::vec3(0.0f))
        << "zero-length joint keeps OFFSET 0 0 0";
}

TEST_F(BvhCmu, RuntimeOrderEqualsFileOrder) {
    Result<Skeleton> s = build_skeleton(cmu().skeleton, file_);
    ASSERT_TRUE(s.ok()) << s.error().to_string();
    for (int i = 0; i < s.value().joint_count(); ++i) EXPECT_EQ(s.value().source_index()[static_cast<size_t>(i)], i);
}

TEST_F(BvhCmu, OffsetsInMetres) {
    const BvhData& d = cmu();
    // "OFFSET 2.49329 -6.85026 0.00000" for LeftKnee in the file.
    const double len_units = std::sqrt(2.49329 * 2.49329 + 6.85026 * 6.85026);
    const glm::vec3 knee = d.skeleton.joints[static_cast<size_t>(find_raw(d.skeleton, "LeftKnee"))].translation;
    EXPECT_NEAR(glm::length(knee), len_units * kScale, kFloatTol);
    // Rest leg chain drop LeftHip..LeftToe = 1.64261 + 6.85026 + 6.50520 + 0.40718 = 15.40525 units;
    // the CMU FAQ quotes "leg chain ~15.4 units", i.e. within 0.05 units (its last quoted digit).
    float drop = 0.0f;
    for (const char* name : {"LeftHip", "LeftKnee", "LeftAnkle", "LeftToe"})
        drop -= d.skeleton.joints[static_cast<size_t>(find_raw(d.skeleton, name))].translation.y;
    EXPECT_NEAR(drop, 15.4f * kScale, 0.05f * kScale);
}

TEST_F(BvhCmu, MotionHeaderAndTracks) {
    const BvhData& d = cmu();
    EXPECT_EQ(d.frame_count, 994);
    EXPECT_NEAR(d.frame_time, 0.0083333f, 1e-9f);  // ".0083333" without a leading zero
    EXPECT_NEAR(d.animation.duration, 993 * 0.0083333f, 1e-4f);
    EXPECT_EQ(d.animation.name, "131_01");
    EXPECT_EQ(d.animation.start_offset, 0.0f);
    ASSERT_EQ(d.animation.tracks.size(), 31u);
    for (size_t j = 0; j < 31; ++j) {
        const RawJointTracks& t = d.animation.tracks[j];
        EXPECT_EQ(t.rotations.values.size(), 994u) << j;
        EXPECT_EQ(t.rotations.times.size(), 994u) << j;
        EXPECT_EQ(t.translations.values.size(), j == 0 ? 994u : 0u) << "only Hips has position channels";
        EXPECT_TRUE(t.scales.values.empty());
        for (size_t k = 1; k < t.rotations.times.size(); ++k) ASSERT_LT(t.rotations.times[k - 1], t.rotations.times[k]);
    }
}

TEST_F(BvhCmu, FirstFrameRootPositionAndHipHeight) {
    const BvhData& d = cmu();
    // First motion row starts "5.2300 16.9002 -33.8986".
    const glm::vec3 p = d.animation.tracks[0].translations.values[0];
    EXPECT_NEAR(p.x, 5.2300f * kScale, kFloatTol);
    EXPECT_NEAR(p.y, 16.9002f * kScale, kFloatTol);
    EXPECT_NEAR(p.z, -33.8986f * kScale, kFloatTol);
    // CMU FAQ: hip height "~17 units ~ 0.96 m"; 17 has two significant digits -> +-0.5 units.
    EXPECT_NEAR(p.y, 0.96f, 0.5f * kScale);
}

TEST_F(BvhCmu, FirstFrameHipsRotationIsZyxIntrinsic) {
    const BvhData& d = cmu();
    // Hips: "Zrotation Yrotation Xrotation" = -5.4029 9.8098 10.4956 in the first row.
    const glm::quat q = glm::angleAxis(glm::radians(-5.4029f), glm::vec3(0, 0, 1)) *
                        glm::angleAxis(glm::radians(9.8098f), glm::vec3(0, 1, 0)) *
                        glm::angleAxis(glm::radians(10.4956f), glm::vec3(1, 0, 0));
    EXPECT_NEAR(std::abs(glm::dot(q, d.animation.tracks[0].rotations.values[0])), 1.0f, 1e-6f);
}

TEST_F(BvhCmu, KeepEndSites) {
    BvhOptions o;
    o.keep_end_sites = true;
    Result<BvhData> r = load_bvh(file_, o);
    ASSERT_TRUE(r.ok()) << r.error().to_string();
    ASSERT_EQ(r.value().skeleton.joints.size(), 38u);
    const int end = find_raw(r.value().skeleton, "LeftToe_End");
    ASSERT_GE(end, 0);
    EXPECT_EQ(r.value().skeleton.joints[static_cast<size_t>(end)].parent, find_raw(r.value().skeleton, "LeftToe"));
    EXPECT_NEAR(r.value().skeleton.joints[static_cast<size_t>(end)].translation.z, 1.13491f * kScale, kFloatTol);
    EXPECT_TRUE(r.value().animation.tracks[static_cast<size_t>(end)].rotations.values.empty());
}

// A single joint with three rotation channels in `order`, one frame of `a b c` degrees.
std::string one_joint(const std::string& order, const std::string& values) {
    return "HIERARCHY\nROOT A\n{\n OFFSET 0 0 0\n CHANNELS 3 " + order + "\n End Site\n {\n  OFFSET 0 1 0\n }\n}\n"
           "MOTION\nFrames: 1\nFrame Time: 0.1\n" + values + "\n";
}

// Rotation matrices written out by hand (column-major glm, right-handed, angle in radians).
glm::mat3 rx(float a) { return glm::mat3(1, 0, 0, 0, std::cos(a), std::sin(a), 0, -std::sin(a), std::cos(a)); }
glm::mat3 ry(float a) { return glm::mat3(std::cos(a), 0, -std::sin(a), 0, 1, 0, std::sin(a), 0, std::cos(a)); }
glm::mat3 rz(float a) { return glm::mat3(std::cos(a), std::sin(a), 0, -std::sin(a), std::cos(a), 0, 0, 0, 1); }

TEST(BvhRotationOrder, ZxyAndZyxFollowTheListedOrder) {
    const float z = glm::radians(30.0f), x = glm::radians(45.0f), y = glm::radians(60.0f);
    Result<BvhData> zxy = parse_bvh(one_joint("Zrotation Xrotation Yrotation", "30 45 60"), "zxy.bvh");
    Result<BvhData> zyx = parse_bvh(one_joint("Zrotation Yrotation Xrotation", "30 60 45"), "zyx.bvh");
    ASSERT_TRUE(zxy.ok()) << zxy.error().to_string();
    ASSERT_TRUE(zyx.ok()) << zyx.error().to_string();
    const glm::mat3 m_zxy = glm::mat3_cast(zxy.value().animation.tracks[0].rotations.values[0]);
    const glm::mat3 m_zyx = glm::mat3_cast(zyx.value().animation.tracks[0].rotations.values[0]);
    const glm::mat3 e_zxy = rz(z) * rx(x) * ry(y);
    const glm::mat3 e_zyx = rz(z) * ry(y) * rx(x);
    float diff_between = 0.0f;
    for (int c = 0; c < 3; ++c)
        for (int r = 0; r < 3; ++r) {
            // Entries are sums of products of sines/cosines in [-1,1]: a few float roundings, 1e-5.
            EXPECT_NEAR(m_zxy[c][r], e_zxy[c][r], 1e-5f);
            EXPECT_NEAR(m_zyx[c][r], e_zyx[c][r], 1e-5f);
            diff_between = std::max(diff_between, std::abs(e_zxy[c][r] - e_zyx[c][r]));
        }
    EXPECT_GT(diff_between, 0.1f) << "the two orders must give visibly different rotations";
}

TEST(BvhParse, LineEndingsTabsAndPartialPositionChannels) {
    // Lone CR, CR LF, tabs, trailing spaces, "+" and ".5" numbers; only an Xposition channel:
    // the Y and Z of the translation keep the OFFSET.
    const std::string text =
        "HIERARCHY\rROOT R\r\n{\t\n\tOFFSET 1 2 3  \n\tCHANNELS 2 Xposition Yrotation \r\n\tEnd Site\n\t{\n\t\tOFFSET 0 1 0\n\t}\n}\n"
        "MOTION\r\nFrames:\t2\r\nFrame Time: .5\r\n+10 .5\r\n-20 -.5\n\n";
    BvhOptions o;
    o.unit_scale = 2.0f;
    Result<BvhData> r = parse_bvh(text, "mixed.bvh", o);
    ASSERT_TRUE(r.ok()) << r.error().to_string();
    const BvhData& d = r.value();
    EXPECT_EQ(d.frame_count, 2);
    EXPECT_FLOAT_EQ(d.animation.duration, 0.5f);
    EXPECT_EQ(d.skeleton.joints[0].translation, glm::vec3(2, 4, 6));
    EXPECT_EQ(d.animation.tracks[0].translations.values[0], glm::vec3(20, 4, 6));
    EXPECT_EQ(d.animation.tracks[0].translations.values[1], glm::vec3(-40, 4, 6));
    const glm::quat expect = glm::angleAxis(glm::radians(-0.5f), glm::vec3(0, 1, 0));
    // dot of two unit quaternions: 4 products rounded in float, ~4 * 2^-24 < 1e-6.
    EXPECT_NEAR(std::abs(glm::dot(d.animation.tracks[0].rotations.values[1], expect)), 1.0f, 1e-6f);
}

TEST(BvhParse, SkeletonOnlyFileHasARestPoseClip) {
    // "Frames: 0" (tools write skeleton-only files, some with "Frame Time: 0"): one key at 0 holding the
    // rest pose, the OFFSETs (not the zero a position channel would read) and no rotation; a note says so.
    for (const char* frame_time : {"0.0333333", "0"}) {
        const std::string text = std::string("HIERARCHY\nROOT Hips\n{\n OFFSET 1 90 2\n CHANNELS 6 Xposition Yposition Zposition Zrotation Xrotation Yrotation\n"
                                             " JOINT Knee\n {\n  OFFSET 0 -40 0\n  CHANNELS 3 Zrotation Xrotation Yrotation\n"
                                             "  End Site\n  {\n   OFFSET 0 -40 0\n  }\n }\n}\nMOTION\nFrames: 0\nFrame Time: ") +
                                 frame_time + "\n";
        BvhOptions o;
        o.unit_scale = 0.01f;
        Result<BvhData> r = parse_bvh(text, "skeleton.bvh", o);
        ASSERT_TRUE(r.ok()) << r.error().to_string();
        const BvhData& d = r.value();
        EXPECT_EQ(d.frame_count, 0);
        EXPECT_EQ(d.animation.duration, 0.0f);
        ASSERT_EQ(d.animation.tracks[0].translations.values.size(), 1u);
        EXPECT_EQ(d.animation.tracks[0].translations.values[0], d.skeleton.joints[0].translation);
        EXPECT_EQ(d.animation.tracks[0].translations.times[0], 0.0f);
        for (const auto& track : d.animation.tracks) {
            ASSERT_EQ(track.rotations.values.size(), 1u);
            EXPECT_EQ(track.rotations.values[0], glm::quat(1, 0, 0, 0));
        }
        ASSERT_EQ(d.notes.size(), 1u);
        EXPECT_NE(d.notes[0].find("Frames: 0"), std::string::npos);
    }
}

TEST(BvhLoad, MissingFileNamesIt) {
    Result<BvhData> r = load_bvh("/nonexistent/dir/walk.bvh");
    ASSERT_FALSE(r.ok());
    EXPECT_EQ(r.error().file, "/nonexistent/dir/walk.bvh");
    EXPECT_NE(r.error().message.find("not found"), std::string::npos);
}

}  // namespace
}  // namespace aloha
