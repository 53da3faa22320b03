#include "engine/anim/skeleton.hpp"

#include <cmath>

namespace aloha {

namespace {
bool finite(const glm::vec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }
bool finite(const glm::quat& q) { return finite(glm::vec3(q.x, q.y, q.z)) && std::isfinite(q.w); }
}  // namespace

int Skeleton::find(std::string_view name) const {
    for (size_t i = 0; i < names_.size(); ++i)
        if (names_[i] == name) return static_cast<int>(i);
    return -1;
}

Result<Skeleton> build_skeleton(const RawSkeleton& raw, const std::string& source_name) {
    const size_t n = raw.joints.size();
    if (n == 0) return make_error(source_name, "skeleton has no joints");
    if (n > 32767) return make_error(source_name, "skeleton has " + std::to_string(n) + " joints; at most 32767 are supported");
    for (size_t i = 0; i < n; ++i) {
        const RawJoint& j = raw.joints[i];
        const std::string where = "joint " + std::to_string(i) + " '" + j.name + "'";
        if (j.parent < -1 || j.parent >= static_cast<int>(n))
            return make_error(source_name, where + ": parent index " + std::to_string(j.parent) + " is out of range");
        if (j.parent == static_cast<int>(i)) return make_error(source_name, where + ": joint is its own parent");
        if (!finite(j.translation) || !finite(j.rotation) || !finite(j.scale))
            return make_error(source_name, where + ": rest transform has a NaN or infinite value");
    }
    // Depth-first order from the roots; detects cycles (joints never reached).
    std::vector<std::vector<int>> children(n);
    std::vector<int> roots;
    for (size_t i = 0; i < n; ++i) {
        if (raw.joints[i].parent < 0) roots.push_back(static_cast<int>(i));
        else children[static_cast<size_t>(raw.joints[i].parent)].push_back(static_cast<int>(i));
    }
    std::vector<int> order;
    order.reserve(n);
    std::vector<int> stack(roots.rbegin(), roots.rend());
    while (!stack.empty()) {
        const int j = stack.back();
        stack.pop_back();
        order.push_back(j);
        const auto& c = children[static_cast<size_t>(j)];
        for (auto it = c.rbegin(); it != c.rend(); ++it) stack.push_back(*it);
    }
    if (order.size() != n) return make_error(source_name, "joint hierarchy has a cycle (some joints never reach a root)");

    std::vector<int> runtime_of(n, -1);
    for (size_t r = 0; r < n; ++r) runtime_of[static_cast<size_t>(order[r])] = static_cast<int>(r);
    Skeleton s;
    s.parents_.resize(n);
    s.names_.resize(n);
    s.rest_t_.resize(n);
    s.rest_r_.resize(n);
    s.rest_s_.resize(n);
    s.limits_.resize(n);
    s.source_index_ = order;
    for (size_t r = 0; r < n; ++r) {
        const RawJoint& j = raw.joints[static_cast<size_t>(order[r])];
        s.parents_[r] = static_cast<int16_t>(j.parent < 0 ? -1 : runtime_of[static_cast<size_t>(j.parent)]);
        s.names_[r] = j.name;
        s.rest_t_[r] = j.translation;
        s.rest_r_[r] = glm::normalize(j.rotation);
        s.rest_s_[r] = j.scale;
    }
    return s;
}

Status set_joint_limits(Skeleton& skeleton, std::span<const std::string> names,
                        std::span<const JointLimit> limits, const std::string& source_name) {
    if (names.size() != limits.size()) return make_error(source_name, "joint limit names and values differ in count");
    for (size_t i = 0; i < names.size(); ++i) {
        const int j = skeleton.find(names[i]);
        if (j < 0) return make_error(source_name, "joint limit for unknown joint '" + names[i] + "'", 0, 0, "/" + names[i]);
        const JointLimit& l = limits[i];
        for (int a = 0; a < 3; ++a)
            if (!(l.min_angles[a] <= l.max_angles[a]))
                return make_error(source_name, "joint '" + names[i] + "': min angle exceeds max angle on axis " + std::to_string(a), 0, 0, "/" + names[i]);
        skeleton.limits_[static_cast<size_t>(j)] = l;
    }
    return {};
}

}  // namespace aloha
