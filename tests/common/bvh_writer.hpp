// Test helper: a built clip written as BVH text, so tests can hand a known motion to the BVH loader in another
// unit (and, with a renamed skeleton, another naming convention).
#pragma once

#include "engine/anim/skeleton.hpp"
#include "systems/motion/clip.hpp"
#include "systems/motion/sampling.hpp"

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/gtx/euler_angles.hpp>

#include <cmath>
#include <sstream>
#include <string>
#include <vector>

namespace aloha::test {

/// BVH text of `clip` on `sk`, whose rest rotations must be identity (the built-in humanoid's, every normalised
/// rig's): OFFSETs are the rest translations times `units_per_metre`, every joint rotates through Zrotation
/// Xrotation Yrotation channels (degrees) and the root also positions. `cycles` repetitions of the clip sampled
/// at `fps`, the root carried on by the clip's travel (root_end - root_start) at each repetition, as a looping walk
/// is played. Leaves get an End Site.
inline std::string bvh_text_of_clip(const Skeleton& sk, const AnimationClip& clip, float units_per_metre, float fps, int cycles) {
    const size_t n = static_cast<size_t>(sk.joint_count());
    std::vector<std::vector<size_t>> children(n);
    for (size_t j = 0; j < n; ++j)
        if (sk.parents()[j] >= 0) children[static_cast<size_t>(sk.parents()[j])].push_back(j);
    std::ostringstream s;
    s.precision(9);
    s << "HIERARCHY\n";
    std::vector<size_t> order;
    auto write = [&](auto&& self, size_t j, int depth) -> void {
        const std::string pad(static_cast<size_t>(depth), '\t');
        const glm::vec3 o = sk.rest_translations()[j] * units_per_metre;
        order.push_back(j);
        s << pad << (depth == 0 ? "ROOT " : "JOINT ") << sk.names()[j] << "\n" << pad << "{\n";
        s << pad << "\tOFFSET " << o.x << " " << o.y << " " << o.z << "\n";
        s << pad << "\tCHANNELS " << (depth == 0 ? "6 Xposition Yposition Zposition " : "3 ") << "Zrotation Xrotation Yrotation\n";
        for (size_t c : children[j]) self(self, c, depth + 1);
        if (children[j].empty()) s << pad << "\tEnd Site\n" << pad << "\t{\n" << pad << "\t\tOFFSET 0 0 0\n" << pad << "\t}\n";
        s << pad << "}\n";
    };
    write(write, 0, 0);
    const int frames = static_cast<int>(std::floor(clip.duration() * fps * static_cast<float>(cycles))) + 1;
    s << "MOTION\nFrames: " << frames << "\nFrame Time: " << 1.0f / fps << "\n";
    std::vector<glm::vec3> tr(n), sc(n);
    std::vector<glm::quat> ro(n);
    const glm::vec3 travel = clip.root_end() - clip.root_start();
    for (int f = 0; f < frames; ++f) {
        const float t = static_cast<float>(f) / fps;
        const int cycle = std::min(cycles - 1, static_cast<int>(std::floor(t / clip.duration())));
        int key = 0;
        float alpha = 0.0f;
        find_key(clip, std::clamp(t - static_cast<float>(cycle) * clip.duration(), 0.0f, clip.duration()), nullptr, &key, &alpha);
        sample_blocks(clip, key, alpha, tr.data(), ro.data(), sc.data());
        const glm::vec3 root = (tr[0] + static_cast<float>(cycle) * travel) * units_per_metre;
        s << root.x << " " << root.y << " " << root.z;
        for (size_t j : order) {
            float z = 0.0f, x = 0.0f, y = 0.0f;
            glm::extractEulerAngleZXY(glm::mat4_cast(ro[j]), z, x, y);
            s << " " << glm::degrees(z) << " " << glm::degrees(x) << " " << glm::degrees(y);
        }
        s << "\n";
    }
    return s.str();
}

}  // namespace aloha::test
