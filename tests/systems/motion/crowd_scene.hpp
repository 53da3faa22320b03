// Test fixture: a small mixed crowd on the CMU-like humanoid (clip playback, kinematic and dynamic
// walks, reaches, look-ats, queued requests with cross-fades, several update intervals) driven by
// one MotionController with the IK and dynamic hooks registered. Used to compare update orders.
#pragma once

#include "systems/motion/controller.hpp"
#include "systems/motion/dynamic/dynamic_hook.hpp"
#include "systems/motion/ik/ik_hooks.hpp"
#include "tests/systems/motion/ik/humanoid.hpp"
#include "tests/systems/motion/motion_test_util.hpp"

#include <memory>
#include <vector>

namespace aloha::test {

/// A controller over `count` characters with per-character requests set up by `setup()`.
struct CrowdScene {
    Skeleton sk = make_humanoid(true);
    ClipLibrary clips;
    ClipId wave = 0;
    std::unique_ptr<MotionController> mc;
    IkHookContext ik;
    DynamicHookContext dyn;
    std::vector<AnimLod> lods;

    /// Builds the scene; `dynamic_every` > 0 makes every such character a dynamic walker.
    explicit CrowdScene(size_t count, size_t dynamic_every = 0) : lods(count) {
        wave = clips.add(make_wave_clip(sk, 31, 1.0f), sk).value();
        mc = std::make_unique<MotionController>(sk, clips, count);
        mc->set_walk_rig(resolve_walk_rig(sk, "humanoid").value());
        register_ik_hooks(*mc, ik);
        register_dynamic_walk_hook(*mc, dyn);
        for (size_t c = 0; c < count; ++c) {
            AnimLod& l = lods[c];
            l.update_interval = static_cast<uint8_t>(1 + c % 3);
            l.ik = c % 2 ? IkSolver::Ccd : IkSolver::Dls;
            l.ik_iterations = static_cast<uint8_t>(2 + c % 5);
            l.walk = dynamic_every && c % dynamic_every == 0 ? WalkMethod::Dynamic : WalkMethod::Kinematic;
            const uint32_t id = static_cast<uint32_t>(c);
            MotionRequest r;
            switch (c % 4) {
                case 0:
                    r.kind = RequestKind::Walk;
                    r.speed = 1.0f + 0.05f * static_cast<float>(c % 7);
                    r.target = glm::vec3(0.3f, 0.0f, 1.0f);
                    break;
                case 1:
                    r.kind = RequestKind::PlayClip;
                    r.clip = wave;
                    r.start_time = 0.01f * static_cast<float>(c);
                    r.duration = 0.4f;
                    break;
                case 2:
                    r.kind = RequestKind::Reach;
                    r.effector = static_cast<int16_t>(sk.find(c % 8 == 2 ? "RightWrist" : "LeftWrist"));
                    r.target = glm::vec3(c % 8 == 2 ? -0.35f : 0.35f, 1.15f, 0.3f);
                    r.duration = 0.5f;
                    break;
                default:
                    r.kind = RequestKind::LookAt;
                    r.target = glm::vec3(1.0f, 1.7f, 2.0f);
                    r.duration = 0.3f;
                    break;
            }
            mc->push_request(id, r);
            // Then a clip, cross-faded in live (from clips/walks) or from a snapshot (IK).
            MotionRequest next;
            next.kind = RequestKind::PlayClip;
            next.clip = wave;
            next.crossfade_s = 0.15f;
            next.duration = 0.6f;
            if (r.kind != RequestKind::Walk) mc->push_request(id, next);
        }
    }
};

}  // namespace aloha::test
