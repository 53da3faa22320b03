// Sole contact points of the dynamic walk from a leg rig: where the kinematic gait puts the feet on the
// ground, so the simulated feet stand where the gait's do.
#include "systems/motion/dynamic/dynamic_hook.hpp"
#include "systems/motion/library/gait_clip.hpp"
#include "systems/motion/library/pose_builder.hpp"

namespace aloha {

std::vector<DynamicContactPoint> dynamic_sole_contacts(const Skeleton& skeleton, const WalkRig& rig) {
    const PoseBuilder rest(skeleton);
    const auto parents = skeleton.parents();
    std::vector<DynamicContactPoint> out;
    // A point given in the model's rest pose, fixed to joint j's frame.
    auto add = [&](int j, const glm::vec3& model_point) {
        out.push_back(DynamicContactPoint{j, glm::inverse(rest.rest_model_rotation(j)) * (model_point - rest.rest_position(j))});
    };
    for (int side = 0; side < 2; ++side) {
        const int ankle = rig.ankle[static_cast<size_t>(side)];
        const int toe = rig.toe[static_cast<size_t>(side)];
        const glm::vec3 a = rest.rest_position(ankle);
        // The gait's ground in the rest model: rig.ankle_height below the ankle.
        const float ground = a.y - rig.ankle_height;
        const FootContacts c = foot_contacts(rig, rest, side);
        add(ankle, a + c.heel);  // the heel the foot lands on
        const glm::vec3 ball = a + c.ball;
        add(ankle, glm::vec3(ball.x, ground, ball.z));  // the sole under the ball the foot rolls over
        if (toe < 0) continue;
        // The toes' tip (the farthest child of the toe joint, on the ground): the toes lie flat in stance.
        glm::vec3 tip = ball;
        for (size_t j = 0; j < parents.size(); ++j)
            if (parents[j] == toe && rest.rest_position(static_cast<int>(j)).z > tip.z) tip = rest.rest_position(static_cast<int>(j));
        if (tip.z > ball.z + 0.01f) add(toe, glm::vec3(tip.x, ground, tip.z));
    }
    return out;
}

}  // namespace aloha
