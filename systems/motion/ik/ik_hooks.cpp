#include "systems/motion/ik/ik_hooks.hpp"

#include "systems/motion/ik/ccd.hpp"
#include "systems/motion/ik/chain_fk.hpp"
#include "systems/motion/ik/dls.hpp"
#include "systems/motion/ik/joint_limits.hpp"

#include <algorithm>
#include <cctype>
#include <string_view>

namespace aloha {

using namespace ik;  // NOLINT: IK helper namespace

namespace {

std::string_view strip_prefix(std::string_view name) {
    constexpr std::string_view kMixamo = "mixamorig:";
    if (name.substr(0, kMixamo.size()) == kMixamo) name.remove_prefix(kMixamo.size());
    return name;
}

bool contains_nocase(std::string_view hay, std::string_view needle) {
    if (needle.size() > hay.size()) return false;
    for (size_t i = 0; i + needle.size() <= hay.size(); ++i) {
        size_t k = 0;
        while (k < needle.size() &&
               std::tolower(static_cast<unsigned char>(hay[i + k])) == static_cast<unsigned char>(needle[k]))
            ++k;
        if (k == needle.size()) return true;
    }
    return false;
}

// Walks `length - 1` parents up from `effector`, never onto the root unless the effector is the root.
int climb(const Skeleton& sk, int effector, int length) {
    int base = effector;
    length = std::clamp(length, 1, kMaxIkChain);
    for (int k = 1; k < length; ++k) {
        const int p = sk.parents()[static_cast<size_t>(base)];
        if (p < 0 || sk.parents()[static_cast<size_t>(p)] < 0) break;  // p is the root: stop below it
        base = p;
    }
    return base;
}

int find_first(const Skeleton& sk, std::initializer_list<const char*> names) {
    for (const char* n : names)
        if (const int j = sk.find(n); j >= 0) return j;
    return -1;
}

// Chain base..effector into `chain` (stack storage); returns its length.
int build_chain(const Skeleton& sk, int base, int effector, std::array<int, kMaxIkChain>& chain) {
    int n = 0;
    for (int j = effector; j >= 0 && n < kMaxIkChain; j = sk.parents()[static_cast<size_t>(j)]) {
        chain[static_cast<size_t>(n++)] = j;
        if (j == base) break;
    }
    std::reverse(chain.begin(), chain.begin() + n);
    return n;
}

// Weight of the IK result: 0 -> 1 over the request's cross-fade, smoothstep so it starts and ends gently.
float ramp(const MotionRequest& r, float request_time) {
    if (!(r.crossfade_s > 0.0f)) return 1.0f;
    const float x = std::clamp(request_time / r.crossfade_s, 0.0f, 1.0f);
    return x * x * (3.0f - 2.0f * x);
}

glm::mat4 placement_matrix(const Transform& t) {
    glm::mat4 m = glm::mat4_cast(glm::normalize(t.rotation));
    m[0] *= t.scale;
    m[1] *= t.scale;
    m[2] *= t.scale;
    m[3] = glm::vec4(t.position, 1.0f);
    return m;
}

IkResult solve(const Skeleton& sk, std::span<const int> chain, const PoseView& pose, const IkTarget& target,
               const IkSettings& settings, IkSolver solver) {
    return solver == IkSolver::Dls ? solve_dls(sk, chain, pose, target, settings)
                                   : solve_ccd(sk, chain, pose, target, settings);
}

// True when `goal` is closer to the chain's base than the chain is long (a straight chain reaches it).
bool within_reach(std::span<const int> chain, const PoseView& pose, const glm::vec3& goal) {
    float length = 0.0f;
    for (size_t k = 1; k < chain.size(); ++k)
        length += glm::length(matrix_position(pose.model[static_cast<size_t>(chain[k])]) -
                              matrix_position(pose.model[static_cast<size_t>(chain[k - 1])]));
    return glm::length(goal - matrix_position(pose.model[static_cast<size_t>(chain.front())])) < 0.99f * length;
}

// Rotates the chain's base joint by `angle` about the line from it to the effector (clamped to
// the base's limits), which leaves the effector in place and turns the plane of the joints between.
void swivel(const Skeleton& sk, std::span<const int> chain, const PoseView& pose, float angle) {
    const auto base = static_cast<size_t>(chain.front());
    const auto eff = static_cast<size_t>(chain.back());
    const glm::vec3 axis = matrix_position(pose.model[eff]) - matrix_position(pose.model[base]);
    if (glm::length(axis) < 1e-6f) return;
    const glm::quat parent = ik::matrix_rotation(parent_model(sk, pose.model, chain.front()));
    const glm::quat turn = glm::angleAxis(angle, glm::normalize(axis));
    glm::quat local = glm::normalize(glm::inverse(parent) * turn * parent * pose.rotations[base]);
    local = clamp_to_limit(sk.limits()[base], sk.rest_rotations()[base], local);
    pose.rotations[base] = local;
    update_chain_model(sk, chain, pose, 0);
}

// Chain rotations = base -> solution by weight w (nlerp on the shorter arc; 1 = the solution exactly).
void blend_chain(const IkCharacterState& cs, std::span<const int> chain, const PoseView& pose, float w) {
    for (size_t k = 0; k < chain.size(); ++k) {
        const glm::quat a = cs.base[k];
        glm::quat b = cs.solution[k];
        if (glm::dot(a, b) < 0.0f) b = -b;
        pose.rotations[static_cast<size_t>(chain[k])] = glm::normalize(a * (1.0f - w) + b * w);
    }
}

void run_ik(IkHookContext& cx, MethodContext& m, bool look_at) {
    if (m.character >= cx.characters.size() || m.character >= cx.overlays.size() || !m.request || !m.lod || !m.skeleton)
        return;
    const Skeleton& sk = *m.skeleton;
    IkCharacterState& cs = m.layered ? cx.overlays[m.character] : cx.characters[m.character];
    const MotionRequest& r = *m.request;
    const int effector = r.effector >= 0 ? r.effector : (look_at ? cx.default_look_effector : cx.default_reach_effector);
    if (effector < 0 || effector >= sk.joint_count()) return;
    const auto& bases = look_at ? cx.look_base : cx.reach_base;
    std::array<int, kMaxIkChain> chain{};
    const int n = build_chain(sk, bases[static_cast<size_t>(effector)], effector, chain);
    const std::span<const int> chain_span(chain.data(), static_cast<size_t>(n));

    // A new request (or a new chain) captures the chain's base rotations and drops the warm start.
    // A layered overlay over a live request takes the pose beneath as its base every frame.
    const bool restart = m.first || !cs.has_base || cs.effector != effector || cs.length != n;
    if (restart || (m.layered && m.base_is_live)) {
        for (int k = 0; k < n; ++k) cs.base[static_cast<size_t>(k)] = m.pose.rotations[static_cast<size_t>(chain[static_cast<size_t>(k)])];
    }
    if (restart) {
        cs.effector = static_cast<int16_t>(effector);
        cs.length = static_cast<uint8_t>(n);
        cs.has_base = 1;
        cs.warm = 0;
    }
    for (int k = 0; k < n; ++k) m.pose.rotations[static_cast<size_t>(chain[static_cast<size_t>(k)])] = cs.base[static_cast<size_t>(k)];
    update_chain_model(sk, chain_span, m.pose, 0);
    if (m.layered && !(m.layer_weight > 0.0f)) return;  // faded out: the pose beneath
    if (m.lod->ik == IkSolver::None) {
        // A request holds the base pose; an overlay fading out (its LOD lost IK) blends from its last solution.
        if (m.layered && cs.warm) blend_chain(cs, chain_span, m.pose, m.layer_weight);
        return;
    }

    // Target in model space.
    const glm::mat4 to_model = m.transform ? glm::inverse(placement_matrix(*m.transform)) : glm::mat4(1.0f);
    const glm::quat inv_rot = m.transform ? glm::inverse(glm::normalize(m.transform->rotation)) : glm::quat(1, 0, 0, 0);
    const glm::vec3 goal = glm::vec3(to_model * glm::vec4(r.target, 1.0f));
    IkTarget target;
    const auto eff = static_cast<size_t>(effector);
    if (look_at) {
        // Keep the head where the base pose puts it and turn its look axis onto the target.
        const glm::vec3 head = matrix_position(m.pose.model[eff]);
        const glm::quat head_rot = ik::matrix_rotation(m.pose.model[eff]);
        target.position = head;
        target.orientation = glm::normalize(shortest_arc(head_rot * cx.look_axis, goal - head) * head_rot);
        target.use_orientation = true;
        target.orientation_weight = cx.look_orientation_weight;
    } else {
        target.position = goal;
        target.orientation = glm::normalize(inv_rot * r.orientation);
        target.use_orientation = r.use_orientation != 0;
    }
    if (cs.warm) {
        for (int k = 0; k < n; ++k) m.pose.rotations[static_cast<size_t>(chain[static_cast<size_t>(k)])] = cs.solution[static_cast<size_t>(k)];
        update_chain_model(sk, chain_span, m.pose, 0);
    }
    IkSettings settings;
    settings.max_iterations = m.lod->ik_iterations;
    settings.tolerance = m.lod->ik_tolerance;
    settings.damping = cx.damping;
    const IkResult before = cs.last;
    cs.last = solve(sk, chain_span, m.pose, target, settings, m.lod->ik);
    // Stall: a warm-started solve that gained less than 10% on a target within reach is in a local
    // minimum (typically a straight limb whose hinge bends in the wrong plane, a DOF pinned at its
    // limit). Swivel the chain about the base-to-effector axis (the effector does not move; one,
    // two or three quarter turns on successive stalls) and solve again; keep whichever is better,
    // so a target that no plane reaches (joint limits) holds still instead of spinning.
    const auto energy = [&](const IkResult& res) {
        return res.position_error + (target.use_orientation ? target.orientation_weight * res.orientation_error : 0.0f);
    };
    if (!look_at && cs.warm && n >= 3 && !cs.last.converged && settings.max_iterations > 0 &&
        energy(cs.last) > 0.9f * energy(before) && within_reach(chain_span, m.pose, target.position)) {
        std::array<glm::quat, kMaxIkChain> kept{};
        for (int k = 0; k < n; ++k) kept[static_cast<size_t>(k)] = m.pose.rotations[static_cast<size_t>(chain[static_cast<size_t>(k)])];
        const IkResult kept_result = cs.last;
        const float quarter_turns = static_cast<float>(cs.stalls++ % 3 + 1);  // 90, 180, 270 degrees
        swivel(sk, chain_span, m.pose, quarter_turns * 0.5f * 3.14159265f);
        // CCD after the swivel: its exact per-joint optimum leaves the old plane's basin faster.
        cs.last = solve(sk, chain_span, m.pose, target, settings, IkSolver::Ccd);
        if (!(energy(cs.last) < energy(kept_result))) {
            for (int k = 0; k < n; ++k) m.pose.rotations[static_cast<size_t>(chain[static_cast<size_t>(k)])] = kept[static_cast<size_t>(k)];
            update_chain_model(sk, chain_span, m.pose, 0);
            cs.last = kept_result;
        }
    }
    for (int k = 0; k < n; ++k) cs.solution[static_cast<size_t>(k)] = m.pose.rotations[static_cast<size_t>(chain[static_cast<size_t>(k)])];
    cs.warm = 1;

    // Ramp the solution in from the base pose: over the request's cross-fade, or by the overlay's
    // weight (the controller ramps it in seconds).
    const float w = m.layered ? m.layer_weight : ramp(r, m.request_time);
    if (w < 1.0f) blend_chain(cs, chain_span, m.pose, w);
    // The controller recomputes every model matrix after the hook.
}

void reach_hook(void* user, MethodContext& m) { run_ik(*static_cast<IkHookContext*>(user), m, false); }
void look_hook(void* user, MethodContext& m) { run_ik(*static_cast<IkHookContext*>(user), m, true); }

void release_hook(void* user, uint32_t character) {
    auto& cx = *static_cast<IkHookContext*>(user);
    if (character < cx.characters.size()) {
        IkCharacterState& cs = cx.characters[character];
        cs.has_base = 0;
        cs.warm = 0;
        cs.effector = -1;
    }
}

}  // namespace

const std::vector<IkChainRule>& default_ik_chain_rules() {
    static const std::vector<IkChainRule> rules = {
        {"LeftWrist", 3}, {"RightWrist", 3}, {"lhand", 4},     {"rhand", 4},     {"LeftAnkle", 3},
        {"RightAnkle", 3}, {"LeftToe", 4},   {"RightToe", 4},  {"LeftHand", 3},  {"RightHand", 3},
        {"LeftFoot", 3},  {"RightFoot", 3},  {"hand_l", 3},    {"hand_r", 3},    {"foot_l", 3},
        {"foot_r", 3},
    };
    return rules;
}

int ik_chain_base(const Skeleton& sk, const IkHookContext& cx, int effector, bool look_at) {
    if (effector < 0 || effector >= sk.joint_count()) return -1;
    const std::string_view name = strip_prefix(sk.names()[static_cast<size_t>(effector)]);
    if (look_at) {
        // Head/neck chain: the effector plus its ancestors named like a neck or head.
        int base = effector;
        int length = 1;
        for (int p = sk.parents()[static_cast<size_t>(effector)]; p >= 0 && length < kMaxIkChain;
             p = sk.parents()[static_cast<size_t>(p)]) {
            const std::string_view pn = sk.names()[static_cast<size_t>(p)];
            if (!contains_nocase(pn, "neck") && !contains_nocase(pn, "head")) break;
            base = p;
            ++length;
        }
        return length > 1 ? base : climb(sk, effector, cx.look_fallback_length);
    }
    for (const IkChainRule& rule : cx.rules)
        if (strip_prefix(rule.effector) == name) return climb(sk, effector, rule.length);
    return climb(sk, effector, cx.reach_fallback_length);
}

void register_ik_hooks(MotionController& controller, IkHookContext& cx) {
    const Skeleton& sk = controller.skeleton();
    cx.skeleton = &sk;
    const auto n = static_cast<size_t>(sk.joint_count());
    cx.reach_base.assign(n, -1);
    cx.look_base.assign(n, -1);
    for (size_t j = 0; j < n; ++j) {
        cx.reach_base[j] = static_cast<int16_t>(ik_chain_base(sk, cx, static_cast<int>(j), false));
        cx.look_base[j] = static_cast<int16_t>(ik_chain_base(sk, cx, static_cast<int>(j), true));
    }
    cx.default_reach_effector = find_first(sk, {"RightWrist", "RightHand", "mixamorig:RightHand", "hand_r", "rhand"});
    cx.default_look_effector = find_first(sk, {"Head", "mixamorig:Head", "head"});
    cx.characters.assign(controller.capacity(), IkCharacterState{});
    cx.overlays.assign(controller.capacity(), IkCharacterState{});
    controller.set_method_hook(MethodSlot::Reach, &reach_hook, &cx, &release_hook);
    controller.set_method_hook(MethodSlot::LookAt, &look_hook, &cx, &release_hook);
}

}  // namespace aloha
