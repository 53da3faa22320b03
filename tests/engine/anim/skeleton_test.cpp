#include "engine/anim/skeleton.hpp"

#include <gtest/gtest.h>

namespace aloha {
namespace {

TEST(Skeleton, OrdersParentsBeforeChildren) {
    RawSkeleton raw;
    raw.joints = {{"hand", 2, {}, {}, {1, 1, 1}}, {"root", -1, {}, {}, {1, 1, 1}}, {"arm", 1, {}, {}, {1, 1, 1}}};
    auto s = build_skeleton(raw, "test");
    ASSERT_TRUE(s.ok()) << s.error().to_string();
    const Skeleton& sk = s.value();
    ASSERT_EQ(sk.joint_count(), 3);
    for (int i = 0; i < 3; ++i) EXPECT_LT(sk.parents()[static_cast<size_t>(i)], i);
    EXPECT_EQ(sk.names()[0], "root");
    EXPECT_EQ(sk.find("hand"), 2);
    EXPECT_EQ(sk.source_index()[2], 0);
}

TEST(Skeleton, RejectsCyclesAndBadParents) {
    RawSkeleton cyc;
    cyc.joints = {{"a", 1, {}, {}, {1, 1, 1}}, {"b", 0, {}, {}, {1, 1, 1}}};
    auto r = build_skeleton(cyc, "cyc.bvh");
    ASSERT_FALSE(r.ok());
    EXPECT_NE(r.error().to_string().find("cycle"), std::string::npos);
    RawSkeleton bad;
    bad.joints = {{"a", 5, {}, {}, {1, 1, 1}}};
    EXPECT_FALSE(build_skeleton(bad, "bad").ok());
}

TEST(Skeleton, JointLimitsByName) {
    RawSkeleton raw;
    raw.joints = {{"root", -1, {}, {}, {1, 1, 1}}, {"knee", 0, {}, {}, {1, 1, 1}}};
    auto s = build_skeleton(raw, "t");
    ASSERT_TRUE(s.ok());
    std::vector<std::string> names{"knee"};
    std::vector<JointLimit> lim{{glm::vec3(0.0f), glm::vec3(2.5f, 0.0f, 0.0f), true}};
    ASSERT_TRUE(set_joint_limits(s.value(), names, lim, "limits.json").ok());
    EXPECT_TRUE(s.value().limits()[1].limited);
    std::vector<std::string> unknown{"elbow"};
    EXPECT_FALSE(set_joint_limits(s.value(), unknown, lim, "limits.json").ok());
}

}  // namespace
}  // namespace aloha
