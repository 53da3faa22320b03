// Root motion for an in-place cycle from its feet (foot_root_motion.hpp).
#include "systems/motion/library/foot_root_motion.hpp"

#include "systems/motion/clip.hpp"
#include "systems/motion/local_to_model.hpp"
#include "systems/motion/sampling.hpp"

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <cstdio>
#include <vector>

namespace aloha {

namespace {

constexpr float kContact = 0.02f;  // a foot joint within 2 cm of its lowest is on the ground

std::string fixed(float v) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.2f", static_cast<double>(v));
    return buf;
}

}  // namespace

Result<RawAnimation> root_motion_from_feet(const RawAnimation& clip, const Skeleton& skeleton, std::span<const int> contacts, float min_speed,
                                           const std::string& source, float rate, FootRootMotionReport* report) {
    Result<AnimationClip> built = build_clip(clip, skeleton, ClipEncoding::Float32);
    if (!built.ok()) return built.error();
    const AnimationClip& c = built.value();
    const size_t J = static_cast<size_t>(skeleton.joint_count());
    std::vector<size_t> points;
    for (const int a : contacts)
        if (a >= 0 && static_cast<size_t>(a) < J) points.push_back(static_cast<size_t>(a));
    if (points.empty()) return make_error(source, "clip '" + clip.name + "': no foot joints to take root motion from");
    const size_t P = points.size();
    const float duration = c.duration();
    if (!(duration > 0.0f)) return make_error(source, "clip '" + clip.name + "' has no length to take root motion from");
    const int keys = std::max(2, static_cast<int>(std::lround(duration * rate)));
    const float dt = duration / static_cast<float>(keys);

    // Every key's local pose and its contact joints and root in model space.
    std::vector<glm::vec3> tr(J * (keys + 1)), sc(J * (keys + 1));
    std::vector<glm::quat> ro(J * (keys + 1));
    std::vector<glm::mat4> model(J);
    std::vector<glm::vec3> foot((static_cast<size_t>(keys) + 1) * P);  // key-major, P contact joints per key
    std::vector<glm::vec3> root(static_cast<size_t>(keys) + 1);
    for (int k = 0; k <= keys; ++k) {
        const size_t o = static_cast<size_t>(k) * J;
        int key = 0;
        float alpha = 0.0f;
        find_key(c, std::min(static_cast<float>(k) * dt, duration), nullptr, &key, &alpha);
        sample_blocks(c, key, alpha, &tr[o], &ro[o], &sc[o]);
        local_to_model(skeleton.parents().data(), &tr[o], &ro[o], &sc[o], nullptr, model.data(), J);
        for (size_t p = 0; p < P; ++p) foot[static_cast<size_t>(k) * P + p] = glm::vec3(model[points[p]][3]);
        root[static_cast<size_t>(k)] = glm::vec3(model[0][3]);
    }
    const glm::vec3 own = root.back() - root.front();
    if (glm::length(glm::vec2(own.x, own.z)) / duration >= kInPlaceSpeed)
        return make_error(source, "clip '" + clip.name + "' travels (" + fixed(glm::length(glm::vec2(own.x, own.z)) / duration) +
                                      " m/s): it has root motion of its own");

    std::vector<float> lowest(P, FLT_MAX);  // each contact joint's lowest over the clip: where it stands on the ground
    for (size_t i = 0; i < foot.size(); ++i) lowest[i % P] = std::min(lowest[i % P], foot[i].y);
    // The body's horizontal travel at each key: the opposite of the supporting joint's slide.
    // Per step: the supporting joint's slide (the joint nearest its ground at the step's middle, if it is on it),
    // or nothing in flight.
    std::vector<glm::vec2> slide(static_cast<size_t>(keys), glm::vec2(0.0f));
    std::vector<uint8_t> stance(static_cast<size_t>(keys), 0);
    for (size_t k = 0; k < slide.size(); ++k) {
        const glm::vec3* a = &foot[k * P];
        const glm::vec3* b = &foot[(k + 1) * P];
        size_t s = 0;
        float best = FLT_MAX;
        for (size_t p = 0; p < P; ++p) {
            const float above = 0.5f * (a[p].y + b[p].y) - lowest[p];
            if (above < best) best = above, s = p;
        }
        stance[k] = best <= kContact ? 1 : 0;
        slide[k] = glm::vec2(b[s].x - a[s].x, b[s].z - a[s].z);
    }
    // The body's horizontal travel at each key: the opposite of the supporting joint's slide; through a flight it
    // keeps the last stance's velocity (a cycle: a flight at the start continues the stance at its end).
    glm::vec2 velocity(0.0f);
    for (size_t k = 0; k < slide.size(); ++k)
        if (stance[k]) velocity = -slide[k] / dt;
    std::vector<glm::vec2> travel(static_cast<size_t>(keys) + 1, glm::vec2(0.0f));
    int flight = 0;
    for (size_t k = 0; k < slide.size(); ++k) {
        if (stance[k]) velocity = -slide[k] / dt;
        else ++flight;
        travel[k + 1] = travel[k] + velocity * dt;
    }
    const glm::vec2 total = travel.back() / duration;
    if (total.y < min_speed)
        return make_error(source, "clip '" + clip.name + "': its feet carry the body forward at " + fixed(total.y) + " m/s (a walk needs " +
                                      fixed(min_speed) + " m/s or more)");

    RawAnimation out;
    out.name = clip.name;
    out.duration = duration;
    out.start_offset = clip.start_offset;
    out.tracks.resize(J);
    for (int k = 0; k <= keys; ++k) {
        const size_t o = static_cast<size_t>(k) * J;
        const float t = static_cast<float>(k) * dt;
        for (size_t j = 0; j < J; ++j) {
            const RawJointTracks* src = j < clip.tracks.size() ? &clip.tracks[j] : nullptr;
            RawJointTracks& dst = out.tracks[j];
            if (j == 0 || (src && !src->rotations.values.empty())) {
                dst.rotations.times.push_back(t);
                dst.rotations.values.push_back(ro[o + j]);
            }
            if (j == 0 || (src && !src->translations.values.empty())) {
                const glm::vec2 d = j == 0 ? travel[static_cast<size_t>(k)] : glm::vec2(0.0f);
                dst.translations.times.push_back(t);
                dst.translations.values.push_back(tr[o + j] + glm::vec3(d.x, 0.0f, d.y));
            }
            if (src && !src->scales.values.empty()) {
                dst.scales.times.push_back(t);
                dst.scales.values.push_back(sc[o + j]);
            }
        }
    }
    if (report) *report = FootRootMotionReport{total.y, total.x, static_cast<float>(flight) / static_cast<float>(keys)};
    return out;
}

}  // namespace aloha
