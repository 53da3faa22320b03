#include "systems/motion/ik/ik_chain.hpp"

#include "systems/motion/ik/chain_fk.hpp"

#include <algorithm>

namespace aloha {

using namespace ik;

std::vector<int> make_ik_chain(const Skeleton& skeleton, int base_joint, int effector_joint) {
    const int n = skeleton.joint_count();
    if (base_joint < 0 || base_joint >= n || effector_joint < 0 || effector_joint >= n) return {};
    std::vector<int> chain;
    for (int j = effector_joint; j >= 0; j = skeleton.parents()[static_cast<size_t>(j)]) {
        chain.push_back(j);
        if (j == base_joint) {
            if (static_cast<int>(chain.size()) > kMaxIkChain) return {};
            std::reverse(chain.begin(), chain.end());
            return chain;
        }
    }
    return {};
}

namespace ik {

IkError ik_error(const glm::mat4& effector_model, const IkTarget& target) {
    IkError e;
    e.position = glm::length(matrix_position(effector_model) - target.position);
    e.orientation = rotation_angle_between(matrix_rotation(effector_model), glm::normalize(target.orientation));
    e.combined = e.position + (target.use_orientation ? target.orientation_weight * e.orientation : 0.0f);
    return e;
}

IkResult make_ik_result(const IkError& e, int iterations, float tolerance) {
    return IkResult{iterations, e.position, e.orientation, e.combined <= tolerance};
}

}  // namespace ik

}  // namespace aloha
