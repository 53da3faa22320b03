// Motion retargeting between mapped humanoids (retarget.hpp).
#include "systems/motion/library/retarget.hpp"

#include "systems/motion/clip.hpp"
#include "systems/motion/library/pose_builder.hpp"
#include "systems/motion/local_to_model.hpp"
#include "systems/motion/walk_rig.hpp"
#include "systems/motion/sampling.hpp"

#include <glm/gtx/quaternion.hpp>

#include <algorithm>
#include <cassert>
#include <cfloat>
#include <cmath>

namespace aloha {

namespace {

// Model-space rotations and positions of one pose: the motion system's local_to_model, the rotations taken out of
// its matrices (matrix_rotation; normalised rigs have uniform scales).
struct ModelPose {
    std::vector<glm::quat> rotation;
    std::vector<glm::vec3> position;
};

ModelPose model_pose(const Skeleton& sk, const glm::vec3* t, const glm::quat* r, const glm::vec3* s, std::vector<glm::mat4>& scratch) {
    const size_t n = static_cast<size_t>(sk.joint_count());
    scratch.resize(n);
    local_to_model(sk.parents().data(), t, r, s, nullptr, scratch.data(), n);
    ModelPose out;
    out.rotation.resize(n);
    out.position.resize(n);
    for (size_t j = 0; j < n; ++j) {
        out.rotation[j] = matrix_rotation(scratch[j]);
        out.position[j] = glm::vec3(scratch[j][3]);
    }
    return out;
}

ModelPose rest_pose(const Skeleton& sk, std::vector<glm::mat4>& scratch) {
    return model_pose(sk, sk.rest_translations().data(), sk.rest_rotations().data(), sk.rest_scales().data(), scratch);
}

// The lowest of the body's joints (the canonical joints `map` maps): a root on the ground, an Armature node or IK
// helpers are no part of what stands.
float lowest_y(const ModelPose& p, const HumanoidMap& map) {
    float y = FLT_MAX;
    for (const int j : map.joint)
        if (j >= 0) y = std::min(y, p.position[static_cast<size_t>(j)].y);
    return y;
}

// Height of the canonical Hips above the lowest body joint in pose `p`.
float hip_height(const ModelPose& p, const HumanoidMap& map) { return p.position[static_cast<size_t>(map.joint[0])].y - lowest_y(p, map); }

// The canonical joint whose bone (from `c` towards it) aligns `c`: a descendant along `c`'s own chain (same
// side; the spine's centre child, not a collar; fingers before the thumb) mapped in both rigs, or -1.
int bone_end(int c, const HumanoidMap& a, const HumanoidMap& b) {
    const auto joints = canonical_humanoid();
    if (c == 0) return -1;  // Hips: its orientation is the body's, taken as it is
    for (int at = c;;) {
        int next = -1;
        for (int k = at + 1; k < static_cast<int>(joints.size()); ++k) {
            if (joints[static_cast<size_t>(k)].parent != at || joints[static_cast<size_t>(k)].side != joints[static_cast<size_t>(c)].side) continue;
            next = k;
            break;
        }
        if (next < 0) return -1;
        if (a.joint[static_cast<size_t>(next)] >= 0 && b.joint[static_cast<size_t>(next)] >= 0) return next;
        at = next;
    }
}

}  // namespace

float rest_hip_height(const RetargetRig& rig) {
    assert(rig.skeleton && rig.map && rig.map->humanoid);
    std::vector<glm::mat4> scratch;
    return hip_height(rest_pose(*rig.skeleton, scratch), *rig.map);
}

Result<RawAnimation> retarget_clip(const RawAnimation& clip, const RetargetRig& source, const RetargetRig& target, const std::string& name,
                                   RetargetReport* report) {
    for (const RetargetRig* rig : {&source, &target})
        if (rig->skeleton == nullptr || rig->map == nullptr || !rig->map->humanoid)
            return make_error("", std::string(rig == &source ? "the motion's" : "the character's") +
                                      " skeleton is not a mapped humanoid: retargeting needs the canonical joints in both");
    Result<AnimationClip> built = build_clip(clip, *source.skeleton, ClipEncoding::Float32);
    if (!built.ok()) return built.error();
    const AnimationClip& src = built.value();
    const Skeleton& ss = *source.skeleton;
    const Skeleton& ts = *target.skeleton;
    const HumanoidMap& sm = *source.map;
    const HumanoidMap& tm = *target.map;
    const auto joints = canonical_humanoid();

    std::vector<glm::mat4> scratch;
    const ModelPose src_rest = rest_pose(ss, scratch), tgt_rest = rest_pose(ts, scratch);
    const auto s_hips = static_cast<size_t>(sm.joint[0]), t_hips = static_cast<size_t>(tm.joint[0]);
    const float src_height = hip_height(src_rest, sm), tgt_height = hip_height(tgt_rest, tm);
    if (!(src_height > 1e-4f) || !(tgt_height > 1e-4f))
        return make_error("", "a rest pose has its hips at the height of its lowest joint: the pelvis travel cannot be scaled");
    const float k = tgt_height / src_height;

    // The source's poses at its keys, and the ground they stand on: the lowest any joint comes over the clip (a
    // file's rest pose need not stand where its motion does: a BVH's rest hips are often at 0).
    const size_t sn = static_cast<size_t>(ss.joint_count());
    std::vector<ModelPose> poses(src.times().size());
    {
        std::vector<glm::vec3> st(sn), sc(sn);
        std::vector<glm::quat> sr(sn);
        for (size_t i = 0; i < poses.size(); ++i) {
            int key = 0;
            float alpha = 0.0f;
            find_key(src, src.times()[i], nullptr, &key, &alpha);
            sample_blocks(src, key, alpha, st.data(), sr.data(), sc.data());
            poses[i] = model_pose(ss, st.data(), sr.data(), sc.data(), scratch);
        }
    }
    float src_ground = FLT_MAX;
    for (const ModelPose& p : poses) src_ground = std::min(src_ground, lowest_y(p, sm));
    const float tgt_ground = lowest_y(tgt_rest, tm);

    // Per target joint: the source joint it follows and its rest alignment (the model-space change turning the
    // target's rest rotation into the one that points its bone as the source's rest bone points).
    const size_t tn = static_cast<size_t>(ts.joint_count());
    std::vector<int> follows(tn, -1);
    std::vector<glm::quat> align(tn, glm::quat(1, 0, 0, 0));
    RetargetReport rep;
    rep.scale = k;
    for (size_t c = 0; c < joints.size(); ++c) {
        const int sj = sm.joint[c], tj = tm.joint[c];
        if (tj < 0) continue;
        if (sj < 0) {
            rep.kept_at_rest.emplace_back(joints[c].name);
            continue;
        }
        follows[static_cast<size_t>(tj)] = sj;
        const int end = bone_end(static_cast<int>(c), sm, tm);
        if (end < 0) continue;
        const glm::vec3 ds = src_rest.position[static_cast<size_t>(sm.joint[static_cast<size_t>(end)])] - src_rest.position[static_cast<size_t>(sj)];
        const glm::vec3 dt = tgt_rest.position[static_cast<size_t>(tm.joint[static_cast<size_t>(end)])] - tgt_rest.position[static_cast<size_t>(tj)];
        if (glm::length(ds) < 1e-3f || glm::length(dt) < 1e-3f) {
            rep.not_aligned.emplace_back(joints[c].name);
            continue;
        }
        align[static_cast<size_t>(tj)] = glm::rotation(glm::normalize(dt), glm::normalize(ds));
    }

    // The legs: each ankle follows the source's ankle path, scaled as the pelvis travel is, its height above the
    // ground from its own rest height (a foot flat on the ground stays flat on the target's); thigh and knee reach
    // it by two-bone IK, bending as the rotations alone bent the knee, and the foot keeps the rotations' orientation.
    // A foot the source plants is planted on the target: the target moves it k times as far as the source does.
    struct Leg {
        int hip = -1, knee = -1, ankle = -1, source_ankle = -1;
        float source_rest = 0.0f, target_rest = 0.0f;  // rest ankle heights above the rest pose's lowest joint
        float reach = 0.0f;  // thigh + shank, less the 2e-4 m solve_two_bone keeps from full extension
    };
    std::vector<Leg> legs;
    for (const char* side : {"Left", "Right"}) {
        Leg leg{tm.find(std::string(side) + "Hip"), tm.find(std::string(side) + "Knee"), tm.find(std::string(side) + "Ankle"),
                sm.find(std::string(side) + "Ankle")};
        if (leg.hip < 0 || leg.knee < 0 || leg.ankle < 0 || leg.source_ankle < 0) continue;
        leg.source_rest = src_rest.position[static_cast<size_t>(leg.source_ankle)].y - lowest_y(src_rest, sm);
        leg.target_rest = tgt_rest.position[static_cast<size_t>(leg.ankle)].y - tgt_ground;
        const glm::vec3 h = tgt_rest.position[static_cast<size_t>(leg.hip)], kn = tgt_rest.position[static_cast<size_t>(leg.knee)],
                        an = tgt_rest.position[static_cast<size_t>(leg.ankle)];
        leg.reach = glm::length(kn - h) + glm::length(an - kn) - 2e-4f;
        legs.push_back(leg);
    }

    RawAnimation out;
    out.name = name;
    out.duration = src.duration();
    out.start_offset = clip.start_offset;
    out.tracks.resize(tn);
    std::vector<glm::quat> tg(tn);
    std::vector<glm::vec3> tp(tn), tsc(tn);
    // The joint that carries the horizontal travel when it is not the pelvis: the root, when it is the pelvis's
    // ancestor (tn: none).
    size_t carrier = tn;
    for (int a = ts.parents()[t_hips]; a >= 0; a = ts.parents()[static_cast<size_t>(a)])
        if (ts.parents()[static_cast<size_t>(a)] < 0) carrier = static_cast<size_t>(a);
    PoseBuilder pose(ts);
    std::vector<glm::vec3> ankle_path(legs.size());
    for (size_t i = 0; i < poses.size(); ++i) {
        const ModelPose& now = poses[i];
        for (size_t l = 0; l < legs.size(); ++l) {
            const glm::vec3 a = now.position[static_cast<size_t>(legs[l].source_ankle)];
            ankle_path[l] = glm::vec3(k * a.x, tgt_ground + legs[l].target_rest + k * (a.y - src_ground - legs[l].source_rest), k * a.z);
        }
        // The pose from the rotations, the pelvis `drop` below its scaled path.
        auto place = [&](float drop) {
            for (size_t j = 0; j < tn; ++j) {
                const int p = ts.parents()[j];
                const glm::quat parent_r = p < 0 ? glm::quat(1, 0, 0, 0) : tg[static_cast<size_t>(p)];
                const glm::vec3 parent_p = p < 0 ? glm::vec3(0.0f) : tp[static_cast<size_t>(p)];
                const glm::vec3 parent_s = p < 0 ? glm::vec3(1.0f) : tsc[static_cast<size_t>(p)];
                glm::quat local = ts.rest_rotations()[j];
                if (follows[j] >= 0) {
                    const auto s = static_cast<size_t>(follows[j]);
                    const glm::quat model = glm::normalize(now.rotation[s] * glm::inverse(src_rest.rotation[s]) * align[j] * tgt_rest.rotation[j]);
                    local = glm::normalize(glm::inverse(parent_r) * model);
                }
                glm::vec3 translation = ts.rest_translations()[j];
                if (j == carrier) {
                    // A root above the pelvis (Unreal's `root` on the ground) carries the horizontal travel, as such
                    // rigs' own clips do, so the motion system's root motion (joint 0) follows the pelvis.
                    const glm::vec3 at = now.position[s_hips];
                    translation += glm::vec3(k * at.x - tgt_rest.position[t_hips].x, 0.0f, k * at.z - tgt_rest.position[t_hips].z);
                }
                if (j == t_hips) {
                    const glm::vec3 at = now.position[s_hips];
                    const glm::vec3 want(k * at.x, tgt_ground + k * (at.y - src_ground) - drop, k * at.z);
                    translation = (glm::inverse(parent_r) * (want - parent_p)) / parent_s;
                }
                pose.rotations[j] = local;
                pose.translations[j] = translation;
                tg[j] = glm::normalize(parent_r * local);
                tp[j] = parent_p + parent_r * (parent_s * translation);
                tsc[j] = parent_s * ts.rest_scales()[j];
            }
        };
        place(0.0f);
        // Where a leg cannot reach its ankle's path (the target's legs are shorter for its hip height than the
        // source's, or it stands less upright), the pelvis is lowered until it can: the feet stay where the motion
        // puts them. Drop d for a hip at H and path point A, v = A - H, h its horizontal length, L the leg's reach:
        // |v + d y| = L with the ankle below the hip, d = -sqrt(L^2 - h^2) - v.y.
        float drop = 0.0f;
        for (size_t l = 0; l < legs.size(); ++l) {
            const glm::vec3 v = ankle_path[l] - tp[static_cast<size_t>(legs[l].hip)];
            const float h2 = v.x * v.x + v.z * v.z, reach = legs[l].reach;
            if (glm::length(v) <= reach) continue;
            drop = std::max(drop, h2 < reach * reach ? -std::sqrt(reach * reach - h2) - v.y : -v.y);
        }
        if (drop > 0.0f) place(drop);
        rep.pelvis_drop = std::max(rep.pelvis_drop, drop);
        pose.update();
        for (size_t l = 0; l < legs.size(); ++l) {
            const Leg& leg = legs[l];
            const auto hip = static_cast<size_t>(leg.hip), knee = static_cast<size_t>(leg.knee), ankle = static_cast<size_t>(leg.ankle);
            glm::vec3 pole = tp[knee] - 0.5f * (tp[hip] + tp[ankle]);
            if (glm::length(pole) < 1e-4f) pole = tg[t_hips] * glm::vec3(0.0f, 0.0f, 1.0f);  // a straight leg bends forward
            pose.two_bone(leg.hip, leg.knee, leg.ankle, ankle_path[l], glm::normalize(pole));
            pose.set_model_rotation(leg.ankle, tg[ankle]);
            rep.foot_reach_error = std::max(rep.foot_reach_error, glm::length(pose.model_position(leg.ankle) - ankle_path[l]));
        }
        const float time = src.times()[i];
        for (size_t j = 0; j < tn; ++j) {
            if (follows[j] < 0) continue;
            out.tracks[j].rotations.times.push_back(time);
            out.tracks[j].rotations.values.push_back(pose.rotations[j]);
        }
        for (const size_t j : {carrier, t_hips}) {
            if (j == tn) continue;  // no carrier
            out.tracks[j].translations.times.push_back(time);
            out.tracks[j].translations.values.push_back(pose.translations[j]);
        }
    }
    if (report) *report = std::move(rep);
    return out;
}

}  // namespace aloha
