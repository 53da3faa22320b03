// Overlays of the motion controller: a reach or look-at layered over the request a character is
// executing (walk, clip or rest). Only the IK chain is overridden, by a weight that ramps in and out
// in seconds, so the body beneath keeps its motion and nothing snaps when the overlay or the LOD's IK
// comes and goes.
#include "systems/motion/controller.hpp"
#include "systems/motion/local_to_model.hpp"

#include <algorithm>

namespace aloha {

namespace {

float smoothstep01(float x) {
    x = std::clamp(x, 0.0f, 1.0f);
    return x * x * (3.0f - 2.0f * x);
}

bool is_overlay_kind(RequestKind k) { return k == RequestKind::Reach || k == RequestKind::LookAt; }

}  // namespace

bool MotionController::set_overlay(uint32_t character, const MotionRequest& request, float weight) {
    if (character >= chars_.size() || !is_overlay_kind(request.kind)) return false;
    leave_steady(character);  // a steady step has no overlay
    Overlay& o = chars_[character].overlay;
    const bool same = o.on && !o.cleared && o.req.kind == request.kind && o.req.effector == request.effector;
    if (!same) {
        // A new overlay starts from the pose beneath; one still fading out is replaced from where it is.
        o.time = 0.0f;
        o.first = 1;
        if (!o.on) o.presence = 0.0f;
    }
    o.req = request;
    o.weight = std::clamp(weight, 0.0f, 1.0f);
    o.fade_s = std::max(request.crossfade_s, 0.0f);
    o.on = 1;
    o.cleared = 0;
    activate(character);
    return true;
}

void MotionController::clear_overlay(uint32_t character, float seconds) {
    if (character >= chars_.size()) return;
    Overlay& o = chars_[character].overlay;
    if (!o.on) return;
    o.cleared = 1;
    o.fade_s = std::max(seconds, 0.0f);
}

float MotionController::overlay_weight(uint32_t character) const {
    const Overlay& o = chars_[character].overlay;
    return o.on ? o.weight * smoothstep01(o.presence) : 0.0f;
}

void MotionController::advance_overlay(Overlay& o, const AnimLod& lod, float dt) const {
    if (!o.on) return;
    o.time += dt;
    // Gone once it has been shown at weight 0 (the IK chain is then exactly the pose beneath again).
    if (o.cleared && o.presence <= 0.0f && o.shown_zero) {
        o = Overlay{};
        return;
    }
    const float goal = !o.cleared && lod.ik != IkSolver::None ? 1.0f : 0.0f;
    const float step = o.fade_s > 0.0f ? dt / o.fade_s : 1.0f;
    o.presence = goal > o.presence ? std::min(goal, o.presence + step) : std::max(goal, o.presence - step);
}

void MotionController::apply_overlay(uint32_t c, Character& ch, const AnimLod& lod, const PoseView& pose,
                                     Transform& placement, Velocity& velocity, float posed_dt, bool primary) {
    Overlay& o = ch.overlay;
    if (!o.on) return;
    const auto slot = static_cast<size_t>(o.req.kind == RequestKind::Reach ? MethodSlot::Reach : MethodSlot::LookAt);
    if (!hooks_[slot]) return;  // no IK registered: the pose beneath shows
    const int16_t* parents = skeleton_->parents().data();
    const auto n = static_cast<size_t>(skeleton_->joint_count());
    local_to_model(parents, pose.translations.data(), pose.rotations.data(), pose.scales.data(), nullptr, pose.model.data(), n);
    MethodContext ctx{c, &o.req, skeleton_, &lod, pose, &placement, &velocity, posed_dt, o.time, o.first != 0};
    ctx.layered = true;
    ctx.base_is_live = ch.cur.req.kind != RequestKind::Rest;
    ctx.layer_weight = overlay_weight(c);
    hooks_[slot](hook_users_[slot], ctx);
    if (primary) {
        o.first = 0;
        o.shown_zero = ctx.layer_weight <= 0.0f ? 1 : 0;
    }
    local_to_model(parents, pose.translations.data(), pose.rotations.data(), pose.scales.data(), nullptr, pose.model.data(), n);
}

}  // namespace aloha
