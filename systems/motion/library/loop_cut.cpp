#include "systems/motion/library/loop_cut.hpp"

#include "systems/motion/library/loop_seam.hpp"

#include "systems/motion/clip.hpp"
#include "systems/motion/local_to_model.hpp"
#include "systems/motion/sampling.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

namespace aloha {

namespace {

// `v` as a message shows it: 0.6, not 0.600000.
std::string short_number(float v) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%g", static_cast<double>(v));
    return buf;
}

// Heading (yaw about +Y) of a model rotation: the direction its +Z axis points on the ground.
float heading_of(const glm::quat& q) {
    const glm::vec3 f = q * glm::vec3(0, 0, 1);
    return std::atan2(f.x, f.z);
}

float wrap_angle(float a) {
    while (a > 3.14159265f) a -= 6.28318531f;
    while (a < -3.14159265f) a += 6.28318531f;
    return a;
}

// The local pose of `clip` at time t.
void sample_local(const AnimationClip& clip, float t, std::vector<glm::vec3>& tr, std::vector<glm::quat>& ro,
                  std::vector<glm::vec3>& sc) {
    int k = 0;
    float a = 0.0f;
    find_key(clip, std::clamp(t, 0.0f, clip.duration()), nullptr, &k, &a);
    sample_blocks(clip, k, a, tr.data(), ro.data(), sc.data());
}

// Per sampled frame: every joint's position relative to the root on the ground, in the root's
// heading frame, and the root's horizontal position and heading.
struct Frames {
    explicit Frames(size_t n) : joints(n), tr(n), sc(n), ro(n), model(n) {}
    size_t joints = 0;
    std::vector<glm::vec3> rel;   // frame-major, joints per frame
    std::vector<glm::vec2> root;  // horizontal root position
    std::vector<float> heading;
    std::vector<glm::vec3> tr, sc;  // scratch for one frame's local pose
    std::vector<glm::quat> ro;
    std::vector<glm::mat4> model;
};

// Appends the frame of `clip` at time t to `f`.
void add_frame(Frames& f, const AnimationClip& clip, const Skeleton& sk, float t) {
    std::vector<glm::mat4>& model = f.model;
    sample_local(clip, t, f.tr, f.ro, f.sc);
    local_to_model(sk.parents().data(), f.tr.data(), f.ro.data(), f.sc.data(), nullptr, model.data(), f.joints);
    const glm::vec3 r(model[0][3]);
    const float h = heading_of(glm::quat_cast(glm::mat3(model[0])));
    const glm::quat inv = glm::angleAxis(-h, glm::vec3(0, 1, 0));
    for (size_t j = 0; j < f.joints; ++j) f.rel.push_back(inv * (glm::vec3(model[j][3]) - glm::vec3(r.x, 0.0f, r.z)));
    f.root.emplace_back(r.x, r.z);
    f.heading.push_back(h);
}

Frames sample_frames(const AnimationClip& clip, const Skeleton& sk, float step) {
    Frames f(static_cast<size_t>(sk.joint_count()));
    const int count = static_cast<int>(clip.duration() / step) + 1;
    for (int i = 0; i < count; ++i) add_frame(f, clip, sk, static_cast<float>(i) * step);
    return f;
}

// The seam of the whole take as a loop (a cycle authored as one: an in-place walk given root motion): mean joint
// distance between the first and last poses, and how much more the velocity jumps across the seam (the take's last
// step against its first, both over `step`) than it jumps anywhere inside the take (`inside`, the largest mean joint
// change of velocity between consecutive steps): a run's touchdown jolts the feet every step, and a seam at a
// touchdown is no worse than the others.
LoopCut whole_take(const AnimationClip& clip, const Skeleton& sk, float step, float inside) {
    Frames f(static_cast<size_t>(sk.joint_count()));
    const float d = clip.duration();
    for (const float t : {0.0f, step, d - step, d}) add_frame(f, clip, sk, t);
    const size_t J = f.joints;
    const auto p = [&](size_t frame, size_t j) { return f.rel[frame * J + j]; };
    LoopCut out{0.0f, d, 0.0f, 0.0f};
    float jump = 0.0f;
    for (size_t j = 0; j < J; ++j) {
        out.pose_error += glm::length(p(0, j) - p(3, j));
        jump += glm::length((p(1, j) - p(0, j)) - (p(3, j) - p(2, j))) / step;
    }
    out.pose_error /= static_cast<float>(J);
    out.velocity_error = std::max(0.0f, jump / static_cast<float>(J) - inside);
    return out;
}

// The take's joint velocities at the cut's two ends, measured alike: central differences over `h` where the take
// reaches past both ends, else the same one-sided difference at both. False when the loop is the whole take (no
// like measure at its ends). `fix_end` is the heading correction cut_loop puts on the loop's last key, about the
// loop's first root position, turning at `turn_rate` rad/s about +Y throughout.
bool take_rates(const AnimationClip& clip, const LoopCut& cut, float h, const glm::quat& fix_end, float turn_rate,
                const glm::vec3& start_root, SeamRates& out) {
    const float d = clip.duration();
    const bool before = cut.start - h >= 0.0f, after = cut.end + h <= d;
    if (!before && !after) return false;
    const float back = before ? h : 0.0f, ahead = after ? h : 0.0f;  // central with both, one-sided otherwise
    const size_t J = static_cast<size_t>(clip.joint_count());
    std::vector<glm::vec3> tr0(J), tr1(J), sc(J);
    std::vector<glm::quat> ro0(J), ro1(J);
    const glm::vec3 turn(0.0f, turn_rate, 0.0f);
    for (const bool at_end : {false, true}) {
        const float t = at_end ? cut.end : cut.start;
        sample_local(clip, t - back, tr0, ro0, sc);
        sample_local(clip, t + ahead, tr1, ro1, sc);
        std::vector<glm::vec3>& rot = at_end ? out.rotation_end : out.rotation_start;
        std::vector<glm::vec3>& tra = at_end ? out.translation_end : out.translation_start;
        rot.resize(J);
        tra.resize(J);
        for (size_t j = 0; j < J; ++j) {
            rot[j] = rotation_vector(ro1[j] * glm::inverse(ro0[j])) / (back + ahead);
            tra[j] = (tr1[j] - tr0[j]) / (back + ahead);
        }
        // The root as the loop has it: turned by the heading correction (none at the start), which also turns
        // steadily, carrying the root's horizontal offset from where the loop starts round with it.
        if (J == 0) continue;
        const glm::quat fix = at_end ? fix_end : glm::quat(1, 0, 0, 0);
        rot[0] = fix * rot[0] + turn;
        glm::vec3 v = fix * glm::vec3(tra[0].x, 0.0f, tra[0].z);
        if (at_end) {
            sample_local(clip, t, tr0, ro0, sc);
            v += glm::cross(turn, fix * glm::vec3(tr0[0].x - start_root.x, 0.0f, tr0[0].z - start_root.z));
        }
        tra[0] = glm::vec3(v.x, tra[0].y, v.z);
    }
    return true;
}

// The largest mean joint change of velocity between consecutive steps of `f` (sampled every `step` seconds).
float largest_jump_inside(const Frames& f, float step) {
    const size_t J = f.joints, n = f.root.size();
    const auto pose = [&](size_t i, size_t j) { return f.rel[i * J + j]; };
    float inside = 0.0f;
    for (size_t i = 1; i + 1 < n; ++i) {
        float change = 0.0f;
        for (size_t j = 0; j < J; ++j) change += glm::length(pose(i + 1, j) - 2.0f * pose(i, j) + pose(i - 1, j)) / step;
        inside = std::max(inside, change / static_cast<float>(J));
    }
    return inside;
}

}  // namespace

Result<LoopCut> whole_take_seam(const RawAnimation& take, const Skeleton& skeleton, const std::string& source, float step) {
    auto built = build_clip(take, skeleton, ClipEncoding::Float32);
    if (!built.ok()) return built.error();
    const AnimationClip& clip = built.value();
    if (clip.duration() < 3.0f * step)
        return make_error(source, "clip '" + take.name + "' is too short to loop (" + short_number(clip.duration()) + " s)");
    return whole_take(clip, skeleton, step, largest_jump_inside(sample_frames(clip, skeleton, step), step));
}

Result<LoopCut> find_best_loop(const RawAnimation& take, const Skeleton& skeleton, float min_seconds, float min_speed,
                               const std::string& source, float step) {
    auto built = build_clip(take, skeleton);
    if (!built.ok()) return built.error();
    const AnimationClip& clip = built.value();
    if (clip.duration() < min_seconds + 2.0f * step)
        return make_error(source, "clip '" + take.name + "' is shorter than a loop of " + short_number(min_seconds) + " s");
    const Frames f = sample_frames(clip, skeleton, step);
    const size_t n = f.root.size(), J = f.joints;
    const auto pose = [&](size_t i, size_t j) { return f.rel[i * J + j]; };
    const auto velocity = [&](size_t i, size_t j) { return (pose(i + 1, j) - pose(i - 1, j)) / (2.0f * step); };
    const size_t min_frames = static_cast<size_t>(std::ceil(min_seconds / step));
    const size_t max_frames = std::max(min_frames, static_cast<size_t>(10.0f / step));  // loops up to 10 s
    // Ground speed of the root over a quarter-second window round each frame: a walk loop must keep
    // moving throughout (a take's standing start and stop match each other perfectly, but are no walk).
    const size_t half = std::max<size_t>(1, static_cast<size_t>(0.125f / step));
    std::vector<float> speed(n, 0.0f);
    for (size_t i = 0; i < n; ++i) {
        const size_t lo = i >= half ? i - half : 0, hi = std::min(n - 1, i + half);
        speed[i] = hi > lo ? glm::length(f.root[hi] - f.root[lo]) / (static_cast<float>(hi - lo) * step) : 0.0f;
    }
    LoopCut best;
    float best_score = 1e30f;
    bool found = false;
    for (size_t a = 1; a + min_frames + 1 < n; ++a) {
        float slowest = speed[a];
        for (size_t b = a + 1; b + 1 < n && b <= a + max_frames; ++b) {
            slowest = std::min(slowest, speed[b]);
            if (slowest < min_speed) break;
            if (b < a + min_frames) continue;
            float pe = 0.0f, ve = 0.0f;
            for (size_t j = 0; j < J; ++j) {
                pe += glm::length(pose(a, j) - pose(b, j));
                ve += glm::length(velocity(a, j) - velocity(b, j));
            }
            pe /= static_cast<float>(J);
            ve /= static_cast<float>(J);
            const float score = pe + 0.1f * ve;  // 0.1 s: a velocity mismatch shows within a few frames
            if (score < best_score) {
                best_score = score;
                best = LoopCut{static_cast<float>(a) * step, static_cast<float>(b) * step, pe, ve};
                found = true;
            }
        }
    }
    // The whole take, when it keeps moving throughout: a cycle authored as one loops at its ends, which the search
    // above (velocities need a frame either side) cannot cut.
    if (clip.duration() >= min_seconds && *std::min_element(speed.begin(), speed.end()) >= min_speed) {
        const LoopCut whole = whole_take(clip, skeleton, step, largest_jump_inside(f, step));
        const float score = whole.pose_error + 0.1f * whole.velocity_error;
        if (score < best_score) best_score = score, best = whole, found = true;
    }
    if (!found)
        return make_error(source, "clip '" + take.name + "' has no stretch of " + short_number(min_seconds) +
                                      " s travelling at " + short_number(min_speed) + " m/s or more to loop");
    if (best.pose_error > kMaxLoopPoseError || best.velocity_error > kMaxLoopVelocityError) {
        char buf[256];
        std::snprintf(buf, sizeof buf,
                      "clip '%s' does not loop: its best loop (%.2f-%.2f s) differs at the seam by %.1f cm per joint "
                      "and %.2f m/s (limits %.1f cm, %.2f m/s); it is played without looping the walk",
                      take.name.c_str(), static_cast<double>(best.start), static_cast<double>(best.end),
                      static_cast<double>(100.0f * best.pose_error), static_cast<double>(best.velocity_error),
                      static_cast<double>(100.0f * kMaxLoopPoseError), static_cast<double>(kMaxLoopVelocityError));
        return make_error(source, buf);
    }
    return best;
}

RawAnimation cut_loop(const RawAnimation& take, const Skeleton& skeleton, const LoopCut& cut, const std::string& name) {
    auto built = build_clip(take, skeleton, ClipEncoding::Float32);  // cut from the keys as they are
    RawAnimation out;
    out.name = name;
    if (!built.ok()) return out;
    const AnimationClip& clip = built.value();
    const size_t J = static_cast<size_t>(skeleton.joint_count());
    // Keys at the take's own rate (its key count over its length), evenly spaced over the loop.
    const float rate = clip.duration() > 0.0f ? static_cast<float>(clip.key_count() - 1) / clip.duration() : 30.0f;
    const int keys = std::max(2, static_cast<int>(std::lround((cut.end - cut.start) * rate)));
    std::vector<glm::vec3> tr(J), sc(J);
    std::vector<glm::quat> ro(J);
    sample_local(clip, cut.start, tr, ro, sc);
    const glm::vec3 start_root = tr[0];
    const float start_heading = heading_of(ro[0]);
    sample_local(clip, cut.end, tr, ro, sc);
    const float drift = wrap_angle(heading_of(ro[0]) - start_heading);
    out.tracks.resize(J);
    for (int k = 0; k <= keys; ++k) {
        const float u = static_cast<float>(k) / static_cast<float>(keys);
        const float t = u * (cut.end - cut.start);
        sample_local(clip, cut.start + t, tr, ro, sc);
        // Spread the heading drift over the loop, turning about the loop's first root position.
        const glm::quat fix = glm::angleAxis(-drift * u, glm::vec3(0, 1, 0));
        ro[0] = glm::normalize(fix * ro[0]);
        const glm::vec3 d = fix * glm::vec3(tr[0].x - start_root.x, 0.0f, tr[0].z - start_root.z);
        tr[0] = glm::vec3(start_root.x + d.x, tr[0].y, start_root.z + d.z);
        for (size_t j = 0; j < J; ++j) {
            const RawJointTracks& src = j < take.tracks.size() ? take.tracks[j] : RawJointTracks{};
            RawJointTracks& dst = out.tracks[j];
            if (!src.rotations.values.empty() || j == 0) {
                dst.rotations.times.push_back(t);
                dst.rotations.values.push_back(ro[j]);
            }
            if (!src.translations.values.empty() || j == 0) {
                dst.translations.times.push_back(t);
                dst.translations.values.push_back(tr[j]);
            }
            if (!src.scales.values.empty()) {
                dst.scales.times.push_back(t);
                dst.scales.values.push_back(sc[j]);
            }
        }
    }
    out.duration = cut.end - cut.start;
    SeamRates rates;
    const glm::quat fix_end = glm::angleAxis(-drift, glm::vec3(0, 1, 0));
    const bool like = take_rates(clip, cut, 1.0f / rate, fix_end, -drift / out.duration, start_root, rates);
    close_loop_seam(out, like ? &rates : nullptr);
    return out;
}

}  // namespace aloha
