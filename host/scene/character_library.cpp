// The generated motion library retargeted onto a character from a file (character_library.hpp).
#include "host/scene/character_library.hpp"

#include "engine/anim/humanoid_map.hpp"
#include "engine/assets/humanoid_definition.hpp"
#include "systems/motion/library/motion_library.hpp"
#include "systems/motion/library/retarget.hpp"
#include "systems/motion/walk_rig.hpp"

#include <algorithm>
#include <cfloat>
#include <cstdio>

namespace aloha {

namespace {

// The built-in humanoid the library is made for: skeleton, its map and walk rig.
struct SourceBody {
    Skeleton skeleton;
    HumanoidMap map;
    WalkRig rig;
};

Result<SourceBody> source_body(const HumanoidDefinition& def, float height) {
    Result<Skeleton> skeleton = build_skeleton(humanoid_skeleton(def, HumanoidBody{height, 0.5f}), def.file);
    if (!skeleton.ok()) return skeleton.error();
    Result<HumanoidMap> map = map_humanoid(skeleton.value());
    if (!map.ok()) return map.error();
    if (!map.value().humanoid) return make_error(def.file, "the built-in humanoid definition does not map to the canonical humanoid");
    Result<WalkRig> rig = resolve_walk_rig(skeleton.value(), map.value(), def.file);
    if (!rig.ok()) return rig.error();
    stand_rig_on_rest_ground(rig.value(), skeleton.value());
    return SourceBody{std::move(skeleton).value(), std::move(map).value(), std::move(rig).value()};
}

// How far from its own speed a type's own walk loop plays before a generated gait takes over: the cadence warped
// by a quarter either way still reads as that walk, brisk or slow; a walk at twice its cadence reads as no run.
constexpr float kOwnLoopReach = 1.25f;

}  // namespace

Status add_generated_motion(CharacterType& type, const CharacterTypeDesc& desc) {
    if (!desc.generated_motion || !type.map.humanoid || desc.canonical.empty()) return {};
    Result<HumanoidDefinition> def = load_humanoid_definition(desc.canonical);
    if (!def.ok()) return def.error();
    // The unit skeleton scales with height: one body at the reference height gives the height whose hips stand
    // as high as the type's, so the gaits' strides and cadences are those of legs this long (scale 1).
    Result<SourceBody> reference = source_body(def.value(), def.value().reference_height);
    if (!reference.ok()) return reference.error();
    const float target_hips = rest_hip_height({&type.skeleton, &type.map});
    const float reference_hips = rest_hip_height({&reference.value().skeleton, &reference.value().map});
    const float height = std::clamp(def.value().reference_height * target_hips / reference_hips, 0.5f, 2.5f);
    Result<SourceBody> body = source_body(def.value(), height);
    if (!body.ok()) return body.error();
    const SourceBody& src = body.value();

    const std::string prefix = desc.clip_prefix.empty() ? desc.name : desc.clip_prefix;
    const std::string& file = desc.bvh.empty() ? desc.gltf : desc.bvh;
    const MotionLibrary lib = make_motion_library(src.skeleton, src.rig, prefix);
    std::vector<const RawAnimation*> clips;
    for (const RawAnimation& gait : lib.gaits) clips.push_back(&gait);
    for (const RawAnimation* clip : {&lib.idle, &lib.turn, &lib.wave}) clips.push_back(clip);

    std::vector<ClipId> gaits;
    std::string skipped;
    float scale = 1.0f, drop = 0.0f, reach_error = 0.0f;
    for (const RawAnimation* clip : clips) {
        if (type.clips.find(clip->name) >= 0) {
            skipped += (skipped.empty() ? "" : ", ") + clip->name;
            continue;
        }
        RetargetReport report;
        Result<RawAnimation> moved = retarget_clip(*clip, {&src.skeleton, &src.map}, {&type.skeleton, &type.map}, clip->name, &report);
        if (!moved.ok()) {
            Error e = moved.error();
            if (e.file.empty()) e.file = file;
            return e;
        }
        Result<ClipId> id = type.clips.add(moved.value(), type.skeleton);
        if (!id.ok()) {
            Error e = id.error();
            if (e.file.empty()) e.file = file;
            return e;
        }
        scale = report.scale;
        drop = std::max(drop, report.pelvis_drop);
        reach_error = std::max(reach_error, report.foot_reach_error);
        if (clip == &lib.idle && type.idle_clip < 0) type.idle_clip = id.value();
        if (clip != &lib.idle && clip != &lib.turn && clip != &lib.wave) gaits.push_back(id.value());
    }

    char buf[160];
    std::snprintf(buf, sizeof buf, "generated motion retargeted from the built-in humanoid at %.2f m (pelvis travel x%.3f", static_cast<double>(height),
                  static_cast<double>(scale));
    std::string note = buf;
    if (drop > 1e-3f) {
        std::snprintf(buf, sizeof buf, "; pelvis lowered up to %.1f cm for the legs to reach", static_cast<double>(drop * 100.0f));
        note += buf;
    }
    if (reach_error > 1e-3f) {
        std::snprintf(buf, sizeof buf, "; the legs fall short of the feet by up to %.1f cm", static_cast<double>(reach_error * 100.0f));
        note += buf;
    }
    note += "): " + std::to_string(gaits.size()) + " gaits, idle, turn, wave";
    if (type.gait_clips.empty()) {
        type.gait_clips = gaits;
        note += "; the gaits are its walk";
    } else if (!gaits.empty()) {
        // Its own loops walk the speeds they can reach within kOwnLoopReach of their cadence; the generated gaits
        // beyond that join them (a file's walk alone would have to be played at twice its cadence to run).
        float slowest = FLT_MAX, fastest = 0.0f;
        for (const ClipId id : type.gait_clips) {
            const float v = type.clips.find(id)->root_speed();
            slowest = std::min(slowest, v), fastest = std::max(fastest, v);
        }
        std::string joined;
        for (const ClipId id : gaits) {
            const AnimationClip& gait = *type.clips.find(id);
            if (gait.root_speed() >= slowest / kOwnLoopReach && gait.root_speed() <= fastest * kOwnLoopReach) continue;
            type.gait_clips.push_back(id);
            joined += (joined.empty() ? "" : ", ") + gait.name();
        }
        note += "; its own walk loops stay its walk" + (joined.empty() ? std::string() : " with the gaits beyond their reach (" + joined + ")") +
                ", the others play by name";
    }
    if (!skipped.empty()) note += "; left out, the file having clips of these names: " + skipped;
    type.notes.push_back(note);
    return {};
}

}  // namespace aloha
