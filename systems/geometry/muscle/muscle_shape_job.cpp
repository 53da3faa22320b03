#include "systems/geometry/muscle/muscle_shape_job.hpp"

#include "systems/geometry/muscle/superellipsoid.hpp"

#include <algorithm>
#include <cmath>

namespace aloha {

size_t MuscleShapeJob::character_count() const {
    if (muscles == nullptr || muscles->joint_count <= 0) return 0;
    return model.size() / static_cast<size_t>(muscles->joint_count);
}

bool MuscleShapeJob::Validate(std::vector<std::string>* errors) const {
    bool ok = true;
    auto fail = [&](const std::string& what) {
        ok = false;
        if (errors) errors->push_back("MuscleShapeJob: " + what);
    };
    if (muscles == nullptr) {
        fail("no muscle set");
        return false;
    }
    if (muscles->joint_count <= 0) fail("muscle set has no skeleton (joint_count is 0)");
    else if (model.size() % static_cast<size_t>(muscles->joint_count) != 0)
        fail("model has " + std::to_string(model.size()) + " matrices, not a multiple of the joint count " +
             std::to_string(muscles->joint_count));
    const size_t need = character_count() * static_cast<size_t>(muscles->size());
    if (centres.size() < need) fail("centres holds " + std::to_string(centres.size()) + ", needs " + std::to_string(need));
    if (rotations.size() < need) fail("rotations holds " + std::to_string(rotations.size()) + ", needs " + std::to_string(need));
    if (radii.size() < need) fail("radii holds " + std::to_string(radii.size()) + ", needs " + std::to_string(need));
    for (int m = 0; m < muscles->size(); ++m) {
        const size_t u = static_cast<size_t>(m);
        if (muscles->origin_joint[u] < 0 || muscles->origin_joint[u] >= muscles->joint_count ||
            muscles->insertion_joint[u] < 0 || muscles->insertion_joint[u] >= muscles->joint_count)
            fail("muscle " + std::to_string(m) + " has a joint index out of range");
    }
    return ok;
}

void MuscleShapeJob::Run() const {
    const MuscleSet& set = *muscles;
    const size_t joints = static_cast<size_t>(set.joint_count);
    const size_t count = static_cast<size_t>(set.size());
    const size_t characters = character_count();
    for (size_t c = 0; c < characters; ++c) {
        const glm::mat4* mats = model.data() + c * joints;
        const size_t out = c * count;
        for (size_t m = 0; m < count; ++m) {
            const glm::mat4& om = mats[set.origin_joint[m]];
            const glm::mat4& im = mats[set.insertion_joint[m]];
            const glm::vec3 o = glm::vec3(om * glm::vec4(set.origin_offset[m], 1.0f));
            const glm::vec3 i = glm::vec3(im * glm::vec4(set.insertion_offset[m], 1.0f));
            const glm::vec3 d = i - o;
            float length = glm::length(d);
            const glm::vec3 x = length > 1e-7f ? d / length : glm::normalize(glm::vec3(om[0]));
            length = std::max(length, 1e-4f);  // a collapsed muscle keeps a tiny finite length
            // Depth axis carried by the origin bone, made orthogonal to x (Gram-Schmidt).
            glm::vec3 z = glm::mat3(om) * set.depth_hint[m];
            z -= glm::dot(z, x) * x;
            float zl = glm::length(z);
            if (zl < 1e-4f) {  // hint parallel to the muscle in this pose: fall back to a bone axis
                z = glm::vec3(om[1]) - glm::dot(glm::vec3(om[1]), x) * x;
                zl = glm::length(z);
                if (zl < 1e-4f) {
                    z = glm::vec3(om[2]) - glm::dot(glm::vec3(om[2]), x) * x;
                    zl = glm::length(z);
                }
            }
            z /= zl;
            const glm::vec3 y = glm::cross(z, x);
            centres[out + m] = 0.5f * (o + i);
            rotations[out + m] = glm::quat_cast(glm::mat3(x, y, z));
            radii[out + m] = volume_preserving_radii(length, set.volume[m], set.ratio[m], set.volume_factor[m]);
        }
    }
}

}  // namespace aloha
