// One character's animation as the last frame left it, for measuring motion quality and exporting
// joints (aloha export, aloha profile --motion-metrics): world joint and sole positions, the
// animation level and method in force, and whether a transition is under way.
#pragma once

#include <glm/glm.hpp>

#include <cstdint>
#include <string>
#include <vector>

namespace aloha {

/// Filled by World::motion_sample; reuse one across calls to keep its storage.
struct MotionSample {
    uint16_t type = 0;             ///< character type index
    uint32_t id = 0;               ///< id within the type
    uint8_t anim_level = 0;        ///< animation level in force
    uint8_t update_interval = 1;   ///< that level's update interval (frames)
    std::string method;            ///< "clip", "kinematic" or "dynamic" while walking; else "play_clip", "rest"
    bool in_transition = false;    ///< a level change or request change is still being blended in
    bool walking = false;          ///< the current request is a walk
    glm::vec3 root{0.0f};          ///< the character's placement (world, on the ground)
    std::vector<glm::vec3> joints; ///< every joint's world position, skeleton order
    std::vector<glm::vec3> soles;  ///< world sole point under each foot joint (ankles, then toes), from
                                   ///< the rest pose's ground (sole_offsets); empty without a leg rig
};

}  // namespace aloha
