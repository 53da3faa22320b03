// Building the rigid links of the dynamic walk: merging zero-length and leaf joints, capsule mass
// and inertia, point-constraint anchors, motor gains, contact points.
#include "systems/motion/dynamic/dynamic_walk.hpp"

#include <algorithm>
#include <cmath>
#include <string>

namespace aloha {

namespace {

bool finite_matrix(const glm::mat4& m) {
    for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r)
            if (!std::isfinite(m[c][r])) return false;
    return true;
}

glm::quat frame_rotation(const glm::mat4& m) {
    return glm::normalize(glm::quat_cast(glm::mat3(glm::normalize(glm::vec3(m[0])), glm::normalize(glm::vec3(m[1])),
                                                   glm::normalize(glm::vec3(m[2])))));
}

// Mass properties accumulated about the body-frame origin.
struct MassSum {
    float mass = 0.0f;
    glm::vec3 first{0.0f};   // sum m * c
    glm::mat3 second{0.0f};  // sum (I_c + m (|c|^2 I - c c^T))
};

// Adds a capsule from a to b (body frame) approximated as a solid cylinder of length L + r.
void add_capsule(MassSum& s, const glm::vec3& a, const glm::vec3& b, float density) {
    const float len = glm::length(b - a);
    const float r = std::clamp(0.15f * len, 0.03f, 0.08f);
    const float m = density * (3.14159265f * r * r * len + 4.0f / 3.0f * 3.14159265f * r * r * r);
    const float l_eff = len + r;
    const float i_axis = 0.5f * m * r * r;
    const float i_perp = m * (3.0f * r * r + l_eff * l_eff) / 12.0f;
    const glm::vec3 u = (b - a) / std::max(len, 1e-6f);
    const glm::vec3 c = 0.5f * (a + b);
    const glm::mat3 uu = glm::outerProduct(u, u);
    const glm::mat3 ic = i_perp * (glm::mat3(1.0f) - uu) + i_axis * uu;
    s.mass += m;
    s.first += m * c;
    s.second += ic + m * (glm::dot(c, c) * glm::mat3(1.0f) - glm::outerProduct(c, c));
}

}  // namespace

glm::vec3 body_joint_position(const DynamicBody& body) { return body.x - body.q * body.com; }

Status init_dynamic_walk(const Skeleton& skeleton, ConstPoseView pose, const glm::mat4& root_world,
                         DynamicWalkState& state, const DynamicWalkSettings& settings) {
    const auto n = static_cast<size_t>(skeleton.joint_count());
    const std::string src = "dynamic walk";
    if (n == 0) return make_error(src, "skeleton has no joints");
    if (pose.translations.size() != n || pose.rotations.size() != n || pose.scales.size() != n || pose.model.size() != n)
        return make_error(src, "start pose spans must all have " + std::to_string(n) + " entries");
    if (!finite_matrix(root_world)) return make_error(src, "root_world has a NaN or infinite value");
    for (size_t j = 0; j < n; ++j)
        if (!finite_matrix(pose.model[j]))
            return make_error(src, "start pose model matrix of joint " + std::to_string(j) + " '" +
                                       skeleton.names()[j] + "' has a NaN or infinite value");
    if (settings.substeps < 1 || !(settings.constraint_frequency > 0.0f) || !(settings.motor_frequency > 0.0f))
        return make_error(src, "settings need substeps >= 1 and positive frequencies");

    const int root = settings.root_joint < 0 ? 0 : settings.root_joint;
    if (static_cast<size_t>(root) >= n)
        return make_error(src, "root joint " + std::to_string(settings.root_joint) + " is not a joint of the " + std::to_string(n) +
                                   "-joint skeleton");
    // Simulated: the root joint and its descendants (parents come before their children).
    std::vector<uint8_t> simulated(n, 0);
    for (size_t j = static_cast<size_t>(root); j < n; ++j)
        simulated[j] = j == static_cast<size_t>(root) ||
                       (skeleton.parents()[j] >= 0 && simulated[static_cast<size_t>(skeleton.parents()[j])]);

    DynamicWalkState s;
    s.settings = settings;
    s.root_joint = root;
    s.root_world = root_world;
    s.translations.assign(pose.translations.begin(), pose.translations.end());
    s.scales.assign(pose.scales.begin(), pose.scales.end());
    s.welded_local.assign(pose.rotations.begin(), pose.rotations.end());
    s.owner.assign(n, -1);
    s.target_world.assign(n, glm::quat(1, 0, 0, 0));
    std::vector<int> child_count(n, 0);
    for (size_t j = 0; j < n; ++j)
        if (skeleton.parents()[j] >= 0) ++child_count[static_cast<size_t>(skeleton.parents()[j])];

    std::vector<glm::vec3> wp(n);
    std::vector<glm::quat> wr(n);
    for (size_t j = 0; j < n; ++j) {
        const glm::mat4 m = root_world * pose.model[j];
        wp[j] = glm::vec3(m[3]);
        wr[j] = frame_rotation(m);
    }
    // A joint owns a body unless it is (nearly) at its parent's position or is a leaf: then it
    // is welded to its parent's body at its start-pose local rotation.
    for (size_t j = 0; j < n; ++j) {
        if (!simulated[j]) continue;
        const int p = skeleton.parents()[j];
        const bool is_root = j == static_cast<size_t>(root);
        const bool own = is_root || (glm::length(wp[j] - wp[static_cast<size_t>(p)]) >= settings.min_bone_length &&
                                     child_count[j] > 0);
        if (own) {
            DynamicBody b;
            b.joint = static_cast<int>(j);
            b.parent = is_root ? -1 : s.owner[static_cast<size_t>(p)];
            s.owner[j] = static_cast<int>(s.bodies.size());
            s.bodies.push_back(b);
        } else {
            s.owner[j] = s.owner[static_cast<size_t>(p)];
        }
    }
    // Mass properties: one capsule per bone (member joint -> child) longer than min_bone_length.
    std::vector<MassSum> sums(s.bodies.size());
    for (size_t c = 0; c < n; ++c) {
        const int m = skeleton.parents()[c];
        if (m < 0 || !simulated[c] || !simulated[static_cast<size_t>(m)]) continue;
        const auto bi = static_cast<size_t>(s.owner[static_cast<size_t>(m)]);
        const DynamicBody& b = s.bodies[bi];
        const auto bj = static_cast<size_t>(b.joint);
        const glm::quat inv = glm::inverse(wr[bj]);
        const glm::vec3 a = inv * (wp[static_cast<size_t>(m)] - wp[bj]);
        const glm::vec3 e = inv * (wp[c] - wp[bj]);
        if (glm::length(e - a) >= settings.min_bone_length) add_capsule(sums[bi], a, e, settings.density);
    }
    for (size_t i = 0; i < s.bodies.size(); ++i) {
        DynamicBody& b = s.bodies[i];
        MassSum& sum = sums[i];
        if (sum.mass < 0.5f) add_capsule(sum, glm::vec3(-0.03f, 0, 0), glm::vec3(0.03f, 0, 0), settings.density);
        b.mass = sum.mass;
        b.com = sum.first / sum.mass;
        // Shift the inertia from the joint origin to the COM (parallel axis theorem, reversed).
        const glm::mat3 shift = b.mass * (glm::dot(b.com, b.com) * glm::mat3(1.0f) - glm::outerProduct(b.com, b.com));
        glm::mat3 inertia = sum.second - shift + glm::mat3(1e-4f);
        b.inv_inertia = glm::inverse(inertia);
        const auto bj = static_cast<size_t>(b.joint);
        b.q = wr[bj];
        b.x = wp[bj] + b.q * b.com;
        if (b.parent >= 0) {
            const DynamicBody& p = s.bodies[static_cast<size_t>(b.parent)];
            b.anchor = glm::inverse(p.q) * (wp[bj] - body_joint_position(p));
        }
        s.total_mass += b.mass;
    }
    // Contact points: the given sole points, else joints near the lowest start-pose joint (feet and toes).
    auto add_contact = [&](size_t j, const glm::vec3& world_point) {
        const auto bi = static_cast<size_t>(s.owner[j]);
        const DynamicBody& b = s.bodies[bi];
        s.contacts.push_back(DynamicContact{static_cast<int>(bi), glm::inverse(b.q) * (world_point - body_joint_position(b))});
    };
    for (const DynamicContactPoint& c : settings.contact_points) {
        if (c.joint < 0 || static_cast<size_t>(c.joint) >= n || !std::isfinite(c.offset.x + c.offset.y + c.offset.z))
            return make_error(src, "contact point on joint " + std::to_string(c.joint) + " is not a joint of the " +
                                       std::to_string(n) + "-joint skeleton or has a non-finite offset");
        const auto j = static_cast<size_t>(c.joint);
        if (!simulated[j])
            return make_error(src, "contact point on joint " + std::to_string(c.joint) + " '" + skeleton.names()[j] +
                                       "' is outside the simulated subtree of root joint '" + skeleton.names()[static_cast<size_t>(root)] + "'");
        add_contact(j, wp[j] + wr[j] * c.offset);
    }
    if (settings.contact_points.empty()) {
        float lowest = wp[static_cast<size_t>(root)].y;
        for (size_t j = 0; j < n; ++j)
            if (simulated[j]) lowest = std::min(lowest, wp[j].y);
        for (size_t j = 0; j < n; ++j)
            if (simulated[j] && wp[j].y <= lowest + settings.contact_height) add_contact(j, wp[j]);
    }
    // Motor gains, k = I w^2 and c = 2 z w I, from the composite inertia I about each joint of the
    // bodies it moves: its subtree; for the legs (the joints between the pelvis and a body that touches
    // the ground) also the rest of the body, which a stance leg carries. A leg tuned to its own subtree
    // alone cannot carry the body's weight (the ankle's own subtree is the foot: ~0.01 kg m^2), so the
    // body sank onto the balance aid, which then bore half its weight and dragged it along: the feet,
    // pressed with half the weight, slid under the friction limit (docs/PERFORMANCE.md, dynamic skate).
    auto in_subtree = [&](size_t k, size_t i) {
        int up = static_cast<int>(k);
        while (up > static_cast<int>(i)) up = s.bodies[static_cast<size_t>(up)].parent;
        return up == static_cast<int>(i);
    };
    // Only with sole contact points: they come with a gait that plants its stance feet; a target that
    // does not (the joint-contact fallback tracks arbitrary rotations) would have stiff legs fight the ground.
    std::vector<uint8_t> carries(s.bodies.size(), 0);
    if (!settings.contact_points.empty())
        for (const DynamicContact& c : s.contacts)
            for (int b = c.body; b > 0; b = s.bodies[static_cast<size_t>(b)].parent) carries[static_cast<size_t>(b)] = 1;
    // A foot whose sole points span less than a tenth of its distance to the pelvis (CesiumMan's: 4 cm)
    // keeps its own gains: a stiff ankle would roll so short a foot over its edge and tip the body.
    for (size_t i = 1; i < s.bodies.size(); ++i) {
        float span = 0.0f;
        int points = 0;
        for (const DynamicContact& a : s.contacts) {
            if (a.body != static_cast<int>(i)) continue;
            ++points;
            for (const DynamicContact& b : s.contacts)
                if (b.body == a.body) span = std::max(span, glm::length(a.local - b.local));
        }
        const float reach = glm::length(body_joint_position(s.bodies[i]) - body_joint_position(s.bodies[0]));
        if (points > 1 && span < 0.1f * reach) carries[i] = 0;
    }
    std::vector<float> sub_inertia(s.bodies.size(), 0.0f);
    std::vector<float> motor_inertia(s.bodies.size(), 0.0f);
    for (size_t i = 0; i < s.bodies.size(); ++i) {
        const glm::vec3 pj = body_joint_position(s.bodies[i]);
        float sub = 0.0f, rest = 0.0f;
        for (size_t k = 0; k < s.bodies.size(); ++k) {
            const DynamicBody& b = s.bodies[k];
            const glm::mat3 inv = b.inv_inertia;
            const float mean_i = (1.0f / inv[0][0] + 1.0f / inv[1][1] + 1.0f / inv[2][2]) / 3.0f;
            const glm::vec3 d = b.x - pj;
            (in_subtree(k, i) ? sub : rest) += b.mass * glm::dot(d, d) + mean_i;
        }
        sub_inertia[i] = sub;
        motor_inertia[i] = carries[i] ? sub + settings.stance_gain * rest : sub;
    }
    const float wm = settings.motor_frequency;
    for (size_t i = 0; i < s.bodies.size(); ++i) {
        s.bodies[i].motor_k = motor_inertia[i] * wm * wm;
        s.bodies[i].motor_c = 2.0f * settings.motor_damping_ratio * wm * motor_inertia[i];
    }
    s.balance_inertia = sub_inertia[0];
    // Solver scratch: rows = 6 per constraint (point + motor), 6 balance rows, 3 per contact.
    const size_t rows = 6 * (s.bodies.size() - 1) + 6 + 3 * s.contacts.size();
    s.row_data.assign(rows * 14, 0.0f);
    s.row_info.assign(rows * 4, 0);
    s.row_mj.assign(rows * 12, 0.0f);
    s.world_inv_inertia.assign(s.bodies.size(), glm::mat3(1.0f));
    s.matrix.assign(rows * rows, 0.0);
    s.work.assign(rows * (3 * s.contacts.size() + 2) + rows, 0.0);
    s.lambda.assign(rows, 0.0);
    s.shift_position.assign(s.bodies.size(), glm::vec3(0.0f));
    s.shift_rotation.assign(s.bodies.size(), glm::vec3(0.0f));
    if (s.bodies.size() < 2) return make_error(src, "skeleton has fewer than two rigid links longer than min_bone_length");
    state = std::move(s);
    return {};
}

float max_constraint_error(const DynamicWalkState& state) {
    float worst = 0.0f;
    for (const DynamicBody& b : state.bodies) {
        if (b.parent < 0) continue;
        const DynamicBody& p = state.bodies[static_cast<size_t>(b.parent)];
        const glm::vec3 on_parent = body_joint_position(p) + p.q * b.anchor;
        worst = std::max(worst, glm::length(body_joint_position(b) - on_parent));
    }
    return worst;
}

}  // namespace aloha
