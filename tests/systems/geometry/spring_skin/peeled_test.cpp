// Peeled layers: linear-blend skinning and rigid proxy boxes.
#include "systems/geometry/spring_skin/peeled.hpp"

#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include <numbers>

namespace aloha {
namespace {

// A three-joint chain: root at origin, then 0.3 m up y, then 0.25 m further, with some twist.
std::vector<glm::mat4> chain_model(float bend) {
    std::vector<glm::mat4> model(3);
    model[0] = glm::rotate(glm::mat4(1.0f), 0.3f, glm::vec3(0, 1, 0));
    model[1] = model[0] * glm::translate(glm::mat4(1.0f), glm::vec3(0, 0.3f, 0)) *
               glm::rotate(glm::mat4(1.0f), bend, glm::vec3(0, 0, 1));
    model[2] = model[1] * glm::translate(glm::mat4(1.0f), glm::vec3(0, 0.25f, 0));
    return model;
}

TEST(LinearBlendSkin, BindPoseIsIdentity) {
    const std::vector<glm::mat4> bind = chain_model(0.4f);
    std::vector<glm::mat4> palette;
    for (const glm::mat4& b : bind) palette.push_back(b * glm::inverse(b));  // model == bind
    std::vector<glm::vec3> p, n, out_p(40), out_n(40);
    std::vector<glm::u16vec4> joints;
    std::vector<glm::vec4> weights;
    for (int i = 0; i < 40; ++i) {
        const float f = static_cast<float>(i);
        p.emplace_back(0.05f * std::sin(f), 0.015f * f, 0.05f * std::cos(f));
        n.push_back(glm::normalize(glm::vec3(std::sin(f), 0.1f, std::cos(f))));
        joints.emplace_back(i % 3, (i + 1) % 3, (i + 2) % 3, 0);
        weights.emplace_back(0.5f, 0.3f, 0.2f, 0.0f);
    }
    LinearBlendSkinJob job{palette, p, n, joints, weights, out_p, out_n};
    std::vector<std::string> errors;
    ASSERT_TRUE(job.Validate(&errors)) << errors.front();
    job.Run();
    // Tolerance: B * inverse(B) differs from identity by a few float ulps (~1e-7 per entry)
    // times coordinates below 1 m.
    for (size_t i = 0; i < p.size(); ++i) {
        EXPECT_NEAR(glm::length(out_p[i] - p[i]), 0.0f, 1e-5f);
        EXPECT_NEAR(glm::length(out_n[i] - n[i]), 0.0f, 1e-5f);
    }
}

TEST(LinearBlendSkin, RigidMotionOfAllJointsMovesTheMeshRigidly) {
    const glm::mat4 motion = glm::translate(glm::mat4(1.0f), glm::vec3(1, 2, 3)) *
                             glm::rotate(glm::mat4(1.0f), 1.1f, glm::normalize(glm::vec3(1, 1, 0)));
    const std::vector<glm::mat4> palette(2, motion);
    const std::vector<glm::vec3> p{{0.1f, 0.2f, 0.3f}}, n{{0, 0, 1}};
    const std::vector<glm::u16vec4> joints{{0, 1, 0, 0}};
    const std::vector<glm::vec4> weights{{0.25f, 0.75f, 0.0f, 0.0f}};
    std::vector<glm::vec3> out_p(1), out_n(1);
    LinearBlendSkinJob job{palette, p, n, joints, weights, out_p, out_n};
    ASSERT_TRUE(job.Validate());
    job.Run();
    EXPECT_NEAR(glm::length(out_p[0] - glm::vec3(motion * glm::vec4(p[0], 1))), 0.0f, 1e-5f);
    EXPECT_NEAR(glm::length(out_n[0] - glm::mat3(motion) * n[0]), 0.0f, 1e-5f);
}

TEST(LinearBlendSkin, ValidateRejectsJointsOutsideThePalette) {
    const std::vector<glm::mat4> palette(2, glm::mat4(1.0f));
    const std::vector<glm::vec3> p(1), n(1);
    const std::vector<glm::u16vec4> joints{{0, 5, 0, 0}};
    const std::vector<glm::vec4> weights{{0.5f, 0.5f, 0, 0}};
    std::vector<glm::vec3> out(1), short_out;
    LinearBlendSkinJob job{palette, p, n, joints, weights, out, short_out};
    std::vector<std::string> errors;
    EXPECT_FALSE(job.Validate(&errors));
    EXPECT_EQ(errors.size(), 2u);  // normals output size, joint 5 outside the palette of 2
}

TEST(RigidProxy, BoxesSpanTheirBones) {
    const std::vector<glm::mat4> model = chain_model(0.7f);
    const std::vector<int16_t> parents{-1, 0, 1};
    std::vector<glm::mat4> boxes(3);
    const float r = 0.04f;
    RigidProxyJob job{model, parents, {}, r, boxes};
    std::vector<std::string> errors;
    ASSERT_TRUE(job.Validate(&errors)) << errors.front();
    job.Run();
    for (size_t j = 1; j < 3; ++j) {
        const glm::vec3 base(model[j - 1][3]), tip(model[j][3]);
        // The cube's -x and +x face centres land on the parent joint and on the joint.
        EXPECT_NEAR(glm::length(glm::vec3(boxes[j] * glm::vec4(-1, 0, 0, 1)) - base), 0.0f, 1e-6f);
        EXPECT_NEAR(glm::length(glm::vec3(boxes[j] * glm::vec4(1, 0, 0, 1)) - tip), 0.0f, 1e-6f);
        // The y/z faces are `r` from the bone axis and perpendicular to it.
        const glm::vec3 axis = glm::normalize(tip - base);
        for (const glm::vec4 side : {glm::vec4(0, 1, 0, 0), glm::vec4(0, 0, 1, 0)}) {
            const glm::vec3 s(boxes[j] * side);
            EXPECT_NEAR(glm::length(s), r, 1e-6f);
            EXPECT_NEAR(glm::dot(s, axis), 0.0f, 1e-6f);
        }
    }
    // The root is a cube of half-extent r at the root joint.
    EXPECT_NEAR(glm::length(glm::vec3(boxes[0][3]) - glm::vec3(model[0][3])), 0.0f, 1e-6f);
    EXPECT_NEAR(glm::length(glm::vec3(boxes[0][0])), r, 1e-6f);
}

TEST(RigidProxy, ValidateRejectsChildrenBeforeParents) {
    const std::vector<glm::mat4> model(2, glm::mat4(1.0f));
    const std::vector<int16_t> parents{1, -1};
    std::vector<glm::mat4> boxes(2);
    RigidProxyJob job{model, parents, {}, 0.0f, boxes};
    std::vector<std::string> errors;
    EXPECT_FALSE(job.Validate(&errors));
    EXPECT_EQ(errors.size(), 2u);  // radius 0, joint 0 with parent 1
}

}  // namespace
}  // namespace aloha
