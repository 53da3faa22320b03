#include "host/scene/character_bounds.hpp"

#include "host/scene/character_runtime.hpp"
#include "systems/geometry/muscle/muscle_set.hpp"
#include "systems/motion/clip.hpp"
#include "systems/motion/local_to_model.hpp"
#include "systems/motion/sampling.hpp"

#include <algorithm>
#include <cassert>
#include <cfloat>
#include <cmath>
#include <optional>

namespace aloha {
namespace {

float horizontal(const glm::vec3& p, const glm::vec3& axis) { return std::hypot(p.x - axis.x, p.z - axis.z); }

glm::vec3 position(const glm::mat4& m) { return glm::vec3(m[3]); }

// Radius of the pose `model` (about its joint 0's vertical line): each joint's horizontal distance
// plus its skin.
float pose_radius(std::span<const glm::mat4> model, std::span<const float> skin) {
    const glm::vec3 axis = position(model[0]);
    float r = 0.0f;
    for (size_t j = 0; j < model.size(); ++j) r = std::max(r, horizontal(position(model[j]), axis) + skin[j]);
    return r;
}

// Per joint: the largest distance to a skin point whose nearest joint it is.
std::vector<float> skin_per_joint(std::span<const glm::vec3> skin, std::span<const glm::mat4> joints, size_t n) {
    std::vector<float> out(n, 0.0f);
    for (const glm::vec3& v : skin) {
        float nearest = FLT_MAX;
        size_t at = 0;
        for (size_t j = 0; j < joints.size() && j < n; ++j) {
            const glm::vec3 d = v - position(joints[j]);
            const float d2 = glm::dot(d, d);
            if (d2 < nearest) nearest = d2, at = j;
        }
        if (nearest < FLT_MAX) out[at] = std::max(out[at], std::sqrt(nearest));
    }
    return out;
}

}  // namespace

TypeExtent measure_type_extent(const Skeleton& skeleton, const ClipLibrary* clips, std::span<const glm::vec3> skin,
                               std::span<const glm::mat4> skin_joints, float fallback_skin) {
    const auto n = static_cast<size_t>(skeleton.joint_count());
    TypeExtent e;
    if (n == 0) return e;
    e.skin = skin.empty() ? std::vector<float>(n, fallback_skin) : skin_per_joint(skin, skin_joints, n);
    e.tip = e.skin;
    e.bone.assign(n, 0.0f);
    e.rest_joint.assign(n, 0.0f);
    const std::vector<glm::mat4> rest = rest_model_matrices(skeleton);
    const std::span<const int16_t> parents = skeleton.parents();
    for (size_t j = 0; j < n; ++j) {
        e.rest_joint[j] = horizontal(position(rest[j]), position(rest[0]));
        if (parents[j] < 0) continue;
        e.bone[j] = glm::length(position(rest[j]) - position(rest[static_cast<size_t>(parents[j])]));
        for (int a = parents[j]; a >= 0; a = parents[static_cast<size_t>(a)]) {
            const auto ai = static_cast<size_t>(a);
            e.tip[ai] = std::max(e.tip[ai], glm::length(position(rest[j]) - position(rest[ai])) + e.skin[j]);
        }
    }
    e.rest_radius = pose_radius(rest, e.skin);
    if (!clips) return e;
    std::vector<glm::vec3> t(n), s(n);
    std::vector<glm::quat> r(n);
    std::vector<glm::mat4> model(n);
    e.clip_radius.assign(clips->size(), e.rest_radius);
    e.clip_travel_radius.assign(clips->size(), e.rest_radius);
    for (size_t c = 0; c < clips->size(); ++c) {
        const AnimationClip* clip = clips->find(static_cast<ClipId>(c));
        if (!clip || static_cast<size_t>(clip->joint_count()) != n) continue;
        const RootMotionTrack& root = clip->root_motion();
        float radius = 0.0f, travel_radius = 0.0f;
        for (int k = 0; k < clip->key_count(); ++k) {
            sample_blocks(*clip, k, 0.0f, t.data(), r.data(), s.data());
            local_to_model(parents.data(), t.data(), r.data(), s.data(), nullptr, model.data(), n);
            travel_radius = std::max(travel_radius, pose_radius(model, e.skin));
            if (root.moves()) {  // as played with root motion: in place
                put_roots_in_place(root.at(clip->times()[static_cast<size_t>(k)]).inverse(), parents, t, r);
                local_to_model(parents.data(), t.data(), r.data(), s.data(), nullptr, model.data(), n);
            }
            radius = std::max(radius, pose_radius(model, e.skin));
        }
        e.clip_radius[c] = radius;
        e.clip_travel_radius[c] = travel_radius;
    }
    return e;
}

float chain_reach_radius(const TypeExtent& extent, const Skeleton& skeleton, int base, int effector) {
    assert(base >= 0 && effector >= 0 && effector < skeleton.joint_count() && base < skeleton.joint_count());
    float length = 0.0f;
    const std::span<const int16_t> parents = skeleton.parents();
    for (int j = effector; j >= 0 && j != base; j = parents[static_cast<size_t>(j)]) length += extent.bone[static_cast<size_t>(j)];
    return extent.rest_joint[static_cast<size_t>(base)] + length + extent.tip[static_cast<size_t>(effector)];
}

void CharacterRuntime::measure_bounds(std::span<const GeomLod> levels) {
    std::vector<glm::vec3> skin;
    std::vector<glm::mat4> joints;
    if (type.mesh) {
        skin = type.mesh->positions;
        for (const glm::mat4& ibm : type.mesh->inverse_bind) joints.push_back(glm::inverse(ibm));
    } else if (type.muscles.size() > 0 && geometry_data) {
        // The generated skin of the richest mesh level (the skin layers are built for the levels anyway).
        std::optional<GeomLod> richest;
        for (const GeomLod& l : usable_levels(levels))
            if ((l.method == GeomMethod::Layered || l.method == GeomMethod::Subdivided || l.method == GeomMethod::SkinnedMesh) &&
                (!richest || l.theta_steps * l.phi_steps > richest->theta_steps * richest->phi_steps))
                richest = l;
        if (richest) {
            std::vector<uint32_t> indices;
            geometry_data->rest_surface(SkinSurfaceKey{richest->theta_steps, richest->phi_steps, 0}, skin, indices);
            joints = rest_model_matrices(type.skeleton);
        }
    }
    // Without any skin (proxies only) each joint's drawn box is at most a tenth of the height wide.
    extent = measure_type_extent(type.skeleton, &type.clips, skin, joints, 0.1f * type.height);
    type.radius = std::max(0.2f, extent.rest_radius);
}

float CharacterRuntime::bounds_radius(const CharacterDesc& c) const {
    float radius = type.radius;
    auto clip = [&](int id) {
        if (id >= 0 && static_cast<size_t>(id) < extent.clip_radius.size()) radius = std::max(radius, extent.clip_radius[static_cast<size_t>(id)]);
    };
    clip(type.idle_clip);  // where a walk or a played clip may end
    bool walks = false;
    for (const RequestDesc& r : c.requests) walks = walks || r.request.kind == RequestKind::Walk;
    auto widen = [&](const RequestDesc& r) {
        switch (r.request.kind) {
            case RequestKind::PlayClip: {
                const int id = find_clip(type, r.clip);
                if (r.request.root_motion == 0 && id >= 0 && static_cast<size_t>(id) < extent.clip_travel_radius.size())
                    radius = std::max(radius, extent.clip_travel_radius[static_cast<size_t>(id)]);
                clip(id);
                return;
            }
            case RequestKind::Walk: {
                const int32_t walk = motion->pick_walk_clip(r.request.speed);
                if (walk >= 0) return clip(walk);
                // No walk clip: the kinematic walk's own cycle, bounded by every clip the type has.
                for (size_t k = 0; k < extent.clip_radius.size(); ++k) clip(static_cast<int>(k));
                return;
            }
            case RequestKind::Reach:
            case RequestKind::LookAt: {
                const bool look_at = r.request.kind == RequestKind::LookAt;
                const int effector = r.effector.empty() ? (look_at ? ik->default_look_effector : ik->default_reach_effector)
                                                        : find_joint(type.skeleton, type.map, r.effector);
                if (effector < 0 || effector >= type.skeleton.joint_count()) return;  // refused by queue_requests
                const std::vector<int16_t>& bases = look_at ? ik->look_base : ik->reach_base;
                const auto at = static_cast<size_t>(effector);
                const int base = at < bases.size() && bases[at] >= 0 ? bases[at] : effector;
                float reach = chain_reach_radius(extent, type.skeleton, base, effector);
                // A reach by a character that never walks: its hand goes no farther out than the target
                // (a target out of reach stretches the chain towards it: the chain's bound).
                if (!look_at && !walks)
                    reach = std::min(reach, std::max(type.radius, std::hypot(r.request.target.x - c.position.x, r.request.target.z - c.position.z) +
                                                                      extent.tip[at]));
                radius = std::max(radius, reach);
                return;
            }
            default:
                return;
        }
    };
    for (const RequestDesc& r : c.requests) widen(r);
    if (c.overlay) widen(*c.overlay);
    return radius;
}

}  // namespace aloha
