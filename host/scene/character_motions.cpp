// Motion files retargeted onto a character type (character_motions.hpp).
#include "host/scene/character_motions.hpp"

#include "engine/assets/gltf_loader.hpp"
#include "host/scene/character_rig.hpp"
#include "systems/motion/clip.hpp"
#include "systems/motion/library/foot_root_motion.hpp"
#include "systems/motion/library/loop_cut.hpp"
#include "systems/motion/library/retarget.hpp"
#include "systems/motion/sampling.hpp"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <tuple>

namespace aloha {

namespace {

// One motion file's clips on its own normalised, mapped skeleton.
struct MotionSource {
    NormalisedRig rig;
    std::vector<RawAnimation> clips;  // named as the clips will be after the type's prefix
    std::string file;
};

// The type description normalise_file_rig reads for a motion file: its map, scale and place in the scene.
CharacterTypeDesc rig_desc(const MotionFileDesc& m, const CharacterTypeDesc& type) {
    CharacterTypeDesc d;
    d.name = type.name;
    d.humanoid_map = m.humanoid_map;
    d.scale = m.scale;
    d.scene_file = type.scene_file;
    d.pointer = m.pointer;
    return d;
}

Result<MotionSource> load_bvh_motion(const MotionFileDesc& m, const CharacterTypeDesc& type) {
    Result<NormalisedBvh> take = load_normalised_bvh(m.bvh, rig_desc(m, type));
    if (!take.ok()) return take.error();
    MotionSource out{std::move(take.value().rig), {std::move(take.value().clip)}, m.bvh};
    out.clips[0].name = m.name.empty() ? std::filesystem::path(m.bvh).stem().string() : m.name;
    return out;
}

Result<MotionSource> load_gltf_motion(const MotionFileDesc& m, const CharacterTypeDesc& type) {
    Result<GltfCharacter> gltf = load_gltf_character(m.gltf);
    if (!gltf.ok()) return gltf.error();
    const GltfCharacter& g = gltf.value();
    Result<Skeleton> original = build_skeleton(g.skeleton, m.gltf);
    if (!original.ok()) return original.error();
    Result<NormalisedRig> rig = normalise_file_rig(original.value(), rig_desc(m, type), RigFormat::Gltf, m.gltf, g.humanoid);
    if (!rig.ok()) return rig.error();
    MotionSource out{std::move(rig).value(), {}, m.gltf};
    std::string names;
    for (size_t i = 0; i < g.clips.size(); ++i) {
        names += (names.empty() ? "'" : ", '") + g.clip_names[i] + "'";
        if (!m.clip.empty() && g.clip_names[i] != m.clip) continue;
        RawAnimation clip = g.clips[i];
        normalise_clip(clip, original.value(), out.rig.change);
        clip.name = !m.name.empty() && !m.clip.empty() ? m.name : g.clip_names[i];
        out.clips.push_back(std::move(clip));
    }
    if (out.clips.empty())
        return make_error(type.scene_file, m.clip.empty() ? m.gltf + " has no animations" : "no animation '" + m.clip + "' in " + m.gltf + " (it has " +
                                                                                             (names.empty() ? "none" : names) + ")",
                          0, 0, m.pointer + (m.clip.empty() ? "/gltf" : "/clip"));
    if (!m.name.empty() && m.clip.empty() && out.clips.size() > 1)
        return make_error(type.scene_file, "'name' names one clip, and " + m.gltf + " has " + std::to_string(out.clips.size()) +
                                               " animations: pick one with 'clip'", 0, 0, m.pointer + "/name");
    if (!m.name.empty()) out.clips[0].name = m.name;
    return out;
}

// Where the loop goes against where the body faces: the cosine between the root's travel over the loop and the
// facing its rotation gives the rest pose's +Z at the loop's start (1 forward, -1 a backward walk, 0 a strafe).
float travel_along_facing(const RawAnimation& take, const Skeleton& skeleton, const LoopCut& cut) {
    Result<AnimationClip> built = build_clip(take, skeleton, ClipEncoding::Float32);
    if (!built.ok()) return 1.0f;  // cut from it already: cannot fail here
    const size_t J = static_cast<size_t>(skeleton.joint_count());
    std::vector<glm::vec3> t0(J), t1(J), s(J);
    std::vector<glm::quat> r0(J), r1(J);
    for (const auto& [time, tr, ro] : {std::tuple{cut.start, &t0, &r0}, std::tuple{cut.end, &t1, &r1}}) {
        int k = 0;
        float alpha = 0.0f;
        find_key(built.value(), time, nullptr, &k, &alpha);
        sample_blocks(built.value(), k, alpha, tr->data(), ro->data(), s.data());
    }
    const glm::vec3 facing = r0[0] * glm::inverse(skeleton.rest_rotations()[0]) * glm::vec3(0, 0, 1);
    const glm::vec2 f(facing.x, facing.z), d(t1[0].x - t0[0].x, t1[0].z - t0[0].z);
    return glm::length(f) > 1e-4f && glm::length(d) > 1e-4f ? glm::dot(glm::normalize(f), glm::normalize(d)) : 1.0f;
}

// Whether `take` stays in place: its root's mean horizontal speed under kInPlaceSpeed (what root_motion_from_feet takes).
bool stays_in_place(const RawAnimation& take, const Skeleton& skeleton) {
    Result<AnimationClip> built = build_clip(take, skeleton, ClipEncoding::Float32);
    return built.ok() && built.value().root_speed() < kInPlaceSpeed;
}

// Longest in-place take given root motion to try as a walk (a cycle is a second or two; a long take in place is
// an idle or a dance, and resampling it would cost load time for nothing).
constexpr float kMaxInPlaceSeconds = 60.0f;

// add_walk_loop, the failure noted only when `note_failure`.
Status walk_loop(CharacterType& type, const RawAnimation& take, const std::string& file, bool note_failure) {
    Result<LoopCut> cut = find_best_loop(take, type.skeleton, 0.6f, 0.5f, file);
    RawAnimation in_place_moved;
    FootRootMotionReport feet;
    const RawAnimation* walk = &take;
    if (!cut.ok() && type.rig && take.duration <= kMaxInPlaceSeconds && stays_in_place(take, type.skeleton)) {
        // An in-place cycle: its feet give it root motion, and that may loop as a walk (or say why they do not).
        const int contacts[] = {type.rig->ankle[0], type.rig->ankle[1], type.rig->toe[0], type.rig->toe[1]};  // toe -1: none
        Result<RawAnimation> moved = root_motion_from_feet(take, type.skeleton, contacts, 0.5f, file, 60.0f, &feet);
        if (moved.ok()) {
            in_place_moved = std::move(moved).value();
            walk = &in_place_moved;
            cut = find_best_loop(in_place_moved, type.skeleton, 0.6f, 0.5f, file);
        } else {
            cut = moved.error();
        }
    }
    if (cut.ok() && travel_along_facing(*walk, type.skeleton, cut.value()) < std::cos(0.7853982f)) {
        char buf[200];
        std::snprintf(buf, sizeof buf, "clip '%s' travels more than 45 degrees away from where the body faces (a backward or sideways step): no walk",
                      take.name.c_str());
        cut = make_error(file, buf);
    }
    if (!cut.ok()) {
        if (note_failure) type.notes.push_back("no clip walk: " + cut.error().message);
        return cut.error();
    }
    std::string name = type.name + ".loop";
    for (int n = 2; type.clips.find(name) >= 0; ++n) name = type.name + ".loop" + std::to_string(n);
    auto id = type.clips.add(cut_loop(*walk, type.skeleton, cut.value(), name), type.skeleton);
    if (!id.ok()) {
        type.notes.push_back("no clip walk: " + id.error().message);
        return id.error();
    }
    type.gait_clips.push_back(id.value());
    char buf[256];
    std::snprintf(buf, sizeof buf, "walk loop '%s' cut from '%s' at %.2f-%.2f s (seam %.1f cm, %.2f m/s)", name.c_str(), take.name.c_str(),
                  static_cast<double>(cut.value().start), static_cast<double>(cut.value().end),
                  static_cast<double>(100.0f * cut.value().pose_error), static_cast<double>(cut.value().velocity_error));
    std::string note = buf;
    if (walk == &in_place_moved) {
        std::snprintf(buf, sizeof buf, "; in place: root motion from its feet, %.2f m/s forward, %.2f sideways", static_cast<double>(feet.speed),
                      static_cast<double>(feet.lateral));
        note += buf;
    }
    type.notes.push_back(note);
    return {};
}

}  // namespace

Status add_walk_loop(CharacterType& type, const RawAnimation& take, const std::string& file) { return walk_loop(type, take, file, true); }

void add_walk_loops(CharacterType& type, std::span<const RawAnimation> takes, const std::string& file) {
    std::string first;
    size_t failed = 0;
    for (const RawAnimation& take : takes) {
        Status s = walk_loop(type, take, file, false);
        if (s.ok()) continue;
        if (failed++ == 0) first = s.error().message;
    }
    if (failed == takes.size() && failed > 0)
        type.notes.push_back("no clip walk: " + first +
                             (failed == 2 ? " (nor does its other clip)" : failed > 2 ? " (nor do its " + std::to_string(failed - 1) + " other clips)" : ""));
}

Status add_motion_files(CharacterType& type, const CharacterTypeDesc& desc, std::vector<LoadedTake>& takes) {
    if (desc.motions.empty()) return {};
    if (!type.map.humanoid)
        return make_error(desc.scene_file, "type '" + desc.name + "' is not a mapped humanoid, and motion files are retargeted through the canonical "
                                               "humanoid joints (give it a 'humanoid_map')", 0, 0, desc.pointer + "/motions");
    const std::string prefix = desc.clip_prefix.empty() ? desc.name : desc.clip_prefix;
    for (const MotionFileDesc& m : desc.motions) {
        Result<MotionSource> source = m.bvh.empty() ? load_gltf_motion(m, desc) : load_bvh_motion(m, desc);
        if (!source.ok()) return source.error();
        const MotionSource& s = source.value();
        if (!s.rig.map.humanoid) {
            std::string missing;
            for (const std::string& j : s.rig.map.missing) missing += (missing.empty() ? "" : ", ") + j;
            return make_error(s.file, "the motion's skeleton is not a humanoid (no " + missing + "): give the motion a 'humanoid_map' (" + desc.scene_file +
                                          " " + m.pointer + ")");
        }
        for (const RawAnimation& clip : s.clips) {
            const std::string name = prefix + "." + clip.name;
            if (type.clips.find(name) >= 0)
                return make_error(desc.scene_file, "clip '" + name + "' already exists on type '" + desc.name + "' (give the motion another 'name')", 0, 0,
                                  m.pointer);
            RetargetReport report;
            Result<RawAnimation> moved = retarget_clip(clip, {&s.rig.skeleton, &s.rig.map}, {&type.skeleton, &type.map}, name, &report);
            if (!moved.ok()) {
                Error e = moved.error();
                if (e.file.empty()) e.file = s.file;
                return e;
            }
            if (m.walk)
                if (Status st = add_walk_loop(type, moved.value(), s.file); !st.ok())
                    return make_error(desc.scene_file, "'walk': clip '" + name + "' cannot be the type's walk: " + st.error().message, 0, 0,
                                      m.pointer + "/walk");
            Result<ClipId> id = type.clips.add(moved.value(), type.skeleton);
            if (!id.ok()) {
                Error e = id.error();
                if (e.file.empty()) e.file = s.file;
                return e;
            }
            takes.push_back({std::move(moved).value(), s.file});
            char buf[96];
            std::snprintf(buf, sizeof buf, "%.3f", static_cast<double>(report.scale));
            std::string note = "clip '" + name + "' retargeted from " + std::filesystem::path(s.file).filename().string() + " (pelvis travel x" + buf;
            if (report.pelvis_drop > 1e-3f) {
                std::snprintf(buf, sizeof buf, "%.1f", static_cast<double>(report.pelvis_drop * 100.0f));
                note += std::string("; pelvis lowered up to ") + buf + " cm for the legs to reach the motion's feet";
            }
            if (report.foot_reach_error > 1e-3f) {
                std::snprintf(buf, sizeof buf, "%.1f", static_cast<double>(report.foot_reach_error * 100.0f));
                note += std::string("; the legs fall short of the motion's feet by up to ") + buf + " cm";
            }
            if (!report.not_aligned.empty()) {
                note += "; bones too short to align, turned as the motion's joint: ";
                for (size_t k = 0; k < report.not_aligned.size(); ++k) note += (k ? ", " : "") + report.not_aligned[k];
            }
            if (!report.kept_at_rest.empty()) {
                note += "; at rest, the motion having none: ";
                for (size_t k = 0; k < report.kept_at_rest.size(); ++k) note += (k ? ", " : "") + report.kept_at_rest[k];
            }
            type.notes.push_back(note + ")");
        }
    }
    return {};
}

}  // namespace aloha
