#include "engine/anim/humanoid_fit.hpp"

#include "engine/anim/rest_pose.hpp"

#include <cmath>
#include <deque>

namespace aloha {

namespace {

glm::vec3 at(const std::vector<glm::mat4>& model, int j) { return glm::vec3(model[static_cast<size_t>(j)][3]); }

// Rotation taking the reference segment a->b onto the target's (identity when either is degenerate).
glm::quat turn(const CanonicalFit& f, int a, int b) {
    const glm::vec3 r = f.reference[static_cast<size_t>(b)] - f.reference[static_cast<size_t>(a)];
    const glm::vec3 t = f.position[static_cast<size_t>(b)] - f.position[static_cast<size_t>(a)];
    if (glm::length(r) < 1e-6f || glm::length(t) < 1e-6f) return glm::quat(1, 0, 0, 0);
    return rotation_between(glm::normalize(r), glm::normalize(t));
}

}  // namespace

CanonicalFit fit_canonical(const Skeleton& target, const HumanoidMap& target_map, const Skeleton& reference,
                           const HumanoidMap& reference_map) {
    const auto canon = canonical_humanoid();
    const size_t n = canon.size();
    const std::vector<glm::mat4> tm = skeleton_rest_model(target), rm = skeleton_rest_model(reference);
    CanonicalFit f;
    f.position.assign(n, glm::vec3(0.0f));
    f.reference.resize(n);
    f.bone_child.assign(n, -1);
    f.alignment.assign(n, glm::quat(1, 0, 0, 0));
    f.bone_angle.assign(n, 0.0f);
    std::vector<std::vector<int>> children(n);
    for (size_t c = 0; c < n; ++c) {
        f.reference[c] = at(rm, reference_map.joint[c]);
        if (canon[c].parent >= 0) children[static_cast<size_t>(canon[c].parent)].push_back(static_cast<int>(c));
    }
    // The bone of a canonical joint points where the reference's first child at a non-zero offset is
    // (the convention of a muscle anchor's "along").
    for (size_t c = 0; c < n; ++c) {
        const int rj = reference_map.joint[c];
        for (int k = rj + 1; k < reference.joint_count(); ++k)
            if (reference.parents()[static_cast<size_t>(k)] == rj && glm::length(reference.rest_translations()[static_cast<size_t>(k)]) > 1e-6f) {
                f.bone_child[c] = reference_map.canonical_of(k);
                break;
            }
    }
    std::vector<bool> known(n, false);
    for (size_t c = 0; c < n; ++c)
        if (target_map.joint[c] >= 0) f.position[c] = at(tm, target_map.joint[c]), known[c] = true;
    // Missing joints between a mapped ancestor and a mapped descendant: the reference's offset from
    // the ancestor, turned and stretched onto the target's ancestor-descendant segment.
    for (size_t c = 0; c < n; ++c) {
        if (known[c]) continue;
        int a = canon[c].parent;
        while (a >= 0 && target_map.joint[static_cast<size_t>(a)] < 0) a = canon[static_cast<size_t>(a)].parent;
        int d = -1;
        std::deque<int> queue(children[c].begin(), children[c].end());
        while (!queue.empty() && d < 0) {
            const int x = queue.front();
            queue.pop_front();
            if (target_map.joint[static_cast<size_t>(x)] >= 0) d = x;
            else queue.insert(queue.end(), children[static_cast<size_t>(x)].begin(), children[static_cast<size_t>(x)].end());
        }
        if (a < 0 || d < 0) continue;
        const glm::vec3 ref_seg = f.reference[static_cast<size_t>(d)] - f.reference[static_cast<size_t>(a)];
        const glm::vec3 seg = f.position[static_cast<size_t>(d)] - f.position[static_cast<size_t>(a)];
        const float stretch = glm::length(ref_seg) > 1e-6f ? glm::length(seg) / glm::length(ref_seg) : 1.0f;
        f.position[c] = f.position[static_cast<size_t>(a)] +
                        stretch * (turn(f, a, d) * (f.reference[c] - f.reference[static_cast<size_t>(a)]));
        known[c] = true;
    }
    // Missing end joints (no mapped descendant): the reference's offset from the parent, turned as the
    // parent's own bone is.
    for (size_t c = 0; c < n; ++c) {
        if (known[c]) continue;
        const int p = canon[c].parent;
        // The turn of the nearest bone above with a length in both skeletons.
        glm::quat q(1, 0, 0, 0);
        for (int b = p, a = p >= 0 ? canon[static_cast<size_t>(p)].parent : -1; a >= 0; b = a, a = canon[static_cast<size_t>(a)].parent)
            if (glm::length(f.reference[static_cast<size_t>(b)] - f.reference[static_cast<size_t>(a)]) > 1e-6f &&
                glm::length(f.position[static_cast<size_t>(b)] - f.position[static_cast<size_t>(a)]) > 1e-6f) {
                q = turn(f, a, b);
                break;
            }
        f.position[c] = f.position[static_cast<size_t>(p)] + q * (f.reference[c] - f.reference[static_cast<size_t>(p)]);
        known[c] = true;
    }
    for (size_t c = 0; c < n; ++c) {
        const int b = f.bone_child[c];
        const int p = canon[c].parent;
        if (b >= 0 && glm::length(f.position[static_cast<size_t>(b)] - f.position[c]) > 1e-6f) {
            f.alignment[c] = turn(f, static_cast<int>(c), b);
            f.bone_angle[c] = 2.0f * std::acos(std::min(1.0f, std::abs(f.alignment[c].w)));
        } else if (p >= 0) {
            f.alignment[c] = f.alignment[static_cast<size_t>(p)];
        }
    }
    return f;
}

}  // namespace aloha
