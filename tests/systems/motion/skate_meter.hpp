// Test helper: contact travel of the built-in humanoid's feet, per touchdown (heel and toe sole points,
// contact within 5 mm of the ground and of the foot's lower point, as in gait_clip_test).
#pragma once

#include "components/transform.hpp"
#include "systems/motion/library/gait_clip.hpp"
#include "systems/motion/library/pose_builder.hpp"
#include "systems/motion/walk_rig.hpp"

#include <glm/glm.hpp>

#include <algorithm>
#include <span>

namespace aloha::test {

/// Travel per contact: the largest horizontal distance a sole point moved from where it touched down.
struct SkateMeter {
    /// Records one frame of `model` placed by `x`, `dt` seconds after the previous one. With dt > 0 a
    /// point is in contact only while also slower than `max_speed` horizontally (issue 15's contact:
    /// low and slow; a swinging foot that grazes the ground is not planted).
    void add(const WalkRig& rig, const PoseBuilder& rest, std::span<const glm::mat4> model, const Transform& x,
             float dt = 0.0f, float max_speed = 0.5f) {
        for (int side = 0; side < 2; ++side) {
            const FootContacts c = foot_contacts(rig, rest, side);
            const glm::mat4 ankle = model[static_cast<size_t>(rig.ankle[side])];
            glm::vec3 pts[2] = {glm::vec3(ankle * glm::vec4(c.heel, 1.0f)),
                                glm::vec3(model[static_cast<size_t>(rig.toe[side])][3]) -
                                    glm::vec3(0.0f, rest.rest_position(rig.toe[side]).y, 0.0f)};
            for (glm::vec3& p : pts) p = x.position + x.rotation * p;
            const float lowest = std::min(pts[0].y, pts[1].y);
            for (int k = 0; k < 2; ++k) {
                const int i = 2 * side + k;
                const float speed = dt > 0.0f ? glm::length(glm::vec2(pts[k].x - last[i].x, pts[k].z - last[i].z)) / dt : 0.0f;
                last[i] = pts[k];
                const bool on = pts[k].y < 0.005f && pts[k].y < lowest + 0.001f && speed < max_speed;
                if (on && !down[i]) start[i] = pts[k], excursion[i] = 0.0f, ++contacts;
                if (on) {
                    excursion[i] = std::max(excursion[i], glm::length(glm::vec2(pts[k].x - start[i].x, pts[k].z - start[i].z)));
                    worst = std::max(worst, excursion[i]);
                }
                if (!on && down[i]) total += excursion[i];
                down[i] = on;
            }
        }
    }
    glm::vec3 start[4], last[4];
    float excursion[4] = {0, 0, 0, 0};
    bool down[4] = {false, false, false, false};
    float total = 0.0f, worst = 0.0f;
    int contacts = 0;
};

}  // namespace aloha::test
