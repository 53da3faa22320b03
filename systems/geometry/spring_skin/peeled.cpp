// Linear-blend skinning and rigid proxy boxes for the peeled geometric levels.
#include "systems/geometry/spring_skin/peeled.hpp"

#include <cassert>
#include <cmath>

namespace aloha {

bool LinearBlendSkinJob::Validate(std::vector<std::string>* errors) const {
    bool ok = true;
    auto fail = [&](std::string message) {
        ok = false;
        if (errors) errors->push_back("LinearBlendSkinJob: " + std::move(message));
    };
    const size_t n = bind_positions.size();
    if (bind_normals.size() != n) fail("bind_normals size differs from bind_positions");
    if (joints.size() != n) fail("joints size differs from bind_positions");
    if (weights.size() != n) fail("weights size differs from bind_positions");
    if (positions.size() != n) fail("positions size differs from bind_positions");
    if (normals.size() != n) fail("normals size differs from bind_positions");
    if (joints.size() == n && weights.size() == n) {
        for (size_t i = 0; i < n; ++i) {
            bool bad = false;
            for (int k = 0; k < 4; ++k) bad |= weights[i][k] != 0.0f && joints[i][k] >= joint_matrices.size();
            if (bad) {
                fail("vertex " + std::to_string(i) + " uses a joint outside the palette of " +
                     std::to_string(joint_matrices.size()));
                break;
            }
        }
    }
    return ok;
}

void LinearBlendSkinJob::Run() const {
    assert(Validate());
    const size_t n = bind_positions.size();
    for (size_t i = 0; i < n; ++i) {
        const glm::u16vec4 j = joints[i];
        const glm::vec4 w = weights[i];
        glm::mat4 m = w.x * joint_matrices[j.x];
        if (w.y != 0.0f) m += w.y * joint_matrices[j.y];
        if (w.z != 0.0f) m += w.z * joint_matrices[j.z];
        if (w.w != 0.0f) m += w.w * joint_matrices[j.w];
        positions[i] = glm::vec3(m * glm::vec4(bind_positions[i], 1.0f));
        const glm::vec3 nn = glm::mat3(m) * bind_normals[i];
        const float len2 = glm::dot(nn, nn);
        normals[i] = len2 > 1e-30f ? nn / std::sqrt(len2) : bind_normals[i];
    }
}

bool RigidProxyJob::Validate(std::vector<std::string>* errors) const {
    bool ok = true;
    auto fail = [&](std::string message) {
        ok = false;
        if (errors) errors->push_back("RigidProxyJob: " + std::move(message));
    };
    const size_t n = model.size();
    if (parents.size() != n) fail("parents size differs from model");
    if (boxes.size() != n) fail("boxes size differs from model");
    if (!radii.empty() && radii.size() != n) fail("radii must be empty or one per joint");
    if (radii.empty() && !(std::isfinite(radius) && radius > 0.0f)) fail("radius must be finite and > 0");
    if (parents.size() == n) {
        for (size_t i = 0; i < n; ++i) {
            if (parents[i] >= static_cast<int>(i) || parents[i] < -1) {
                fail("joint " + std::to_string(i) + " has parent " + std::to_string(parents[i]) +
                     " (parents must precede children)");
                break;
            }
        }
    }
    return ok;
}

void RigidProxyJob::Run() const {
    assert(Validate());
    for (size_t j = 0; j < model.size(); ++j) {
        const float r = radii.empty() ? radius : radii[j];
        const glm::vec3 tip(model[j][3]);
        const int parent = parents[j];
        if (parent < 0) {
            boxes[j] = glm::mat4(glm::vec4(r, 0, 0, 0), glm::vec4(0, r, 0, 0), glm::vec4(0, 0, r, 0), glm::vec4(tip, 1.0f));
            continue;
        }
        const glm::mat4& pm = model[static_cast<size_t>(parent)];
        const glm::vec3 base(pm[3]);
        const glm::vec3 bone = tip - base;
        const float length = glm::length(bone);
        glm::vec3 x = length > 1e-9f ? bone / length : glm::normalize(glm::vec3(pm[0]));
        glm::vec3 y = glm::vec3(pm[1]) - glm::dot(glm::vec3(pm[1]), x) * x;
        if (glm::dot(y, y) < 1e-12f) y = glm::vec3(pm[2]) - glm::dot(glm::vec3(pm[2]), x) * x;
        y = glm::normalize(y);
        const glm::vec3 z = glm::cross(x, y);
        boxes[j] = glm::mat4(glm::vec4(0.5f * length * x, 0.0f), glm::vec4(r * y, 0.0f), glm::vec4(r * z, 0.0f),
                             glm::vec4(0.5f * (base + tip), 1.0f));
    }
}

}  // namespace aloha
