#include "systems/motion/library/motion_library.hpp"

#include "systems/motion/library/gait_clip.hpp"
#include "systems/motion/library/idle_clips.hpp"

#include <cstdio>

namespace aloha {

std::string gait_clip_name(float speed, float hip_height) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%s_%.2f", gait_cycle(speed, hip_height).running ? "run" : "walk",
                  static_cast<double>(speed));
    return buf;
}

MotionLibrary make_motion_library(const Skeleton& skeleton, const WalkRig& rig, const std::string& prefix) {
    const HumanoidJoints joints = find_humanoid_joints(skeleton);
    const float hip_height = rig.ankle_height + rig.leg_length;
    MotionLibrary lib;
    for (float speed : kLibraryGaitSpeeds)
        lib.gaits.push_back(make_gait_clip(skeleton, rig, joints, speed, prefix + "." + gait_clip_name(speed, hip_height)).clip);
    lib.idle = make_idle_clip(skeleton, rig, joints, prefix + ".idle");
    lib.turn = make_turn_clip(skeleton, rig, joints, prefix + ".turn");
    lib.wave = make_wave_clip(skeleton, rig, joints, prefix + ".wave");
    return lib;
}

}  // namespace aloha
