// Motion quality meters for any rig: foot skate (horizontal travel of a foot joint while it is in
// contact, per metre the character walked) and pops (the largest joint jump on a frame where the
// animation changed level or method, against the 95th percentile of ordinary frame-to-frame joint
// motion). Fed with world positions frame by frame; no knowledge of the skeleton beyond which
// joints are feet.
#pragma once

#include "engine/anim/skeleton.hpp"

#include <glm/glm.hpp>

#include <cstddef>
#include <span>
#include <vector>

namespace aloha {

/// Sole points for any rig: for each joint in `feet`, the point straight below it on the rest pose's
/// ground (the height of the rest pose's lowest joint), in that joint's own frame. A posed sole point
/// is model[joint] * (offset, 1). Joints rock about their sole, not about themselves (an ankle moves
/// forward while the heel rolls), so skate is measured on these points rather than on the joints.
[[nodiscard]] std::vector<glm::vec3> sole_offsets(const Skeleton& skeleton, std::span<const int> feet);

/// When a foot (sole) point counts as in contact with the ground.
struct ContactThresholds {
    float height = 0.005f;  ///< m above the lowest height that point reaches in the recording (a foot
                            ///< 5-10 mm up is still landing or lifting off, moving forward: not sliding)
    float speed = 0.5f;     ///< m/s of horizontal speed (a swinging foot moves at about twice the walking speed)
};

/// Horizontal travel of the sole points while in contact, per frame (element i: the step from frame
/// i-1 to i, summed over the feet; element 0 is 0). `soles` is frame-major, `feet` points per frame;
/// a step counts when both ends are within t.height of the lowest height that point reaches in the
/// recording and it moved slower than t.speed over dts[i] seconds.
[[nodiscard]] std::vector<float> contact_travel(std::span<const glm::vec3> soles, size_t feet, std::span<const float> dts,
                                                const ContactThresholds& t);

/// Foot skate of one character over a recording: feed every frame's foot joints (same joints, same
/// order, world metres) and root; the result compares the feet's horizontal travel while in contact
/// with the distance the root travelled.
class FootSkateMeter {
public:
    /// Records one frame `dt` seconds after the previous one (the first frame's dt is ignored).
    /// `feet` must have the same size on every frame.
    void add(std::span<const glm::vec3> feet, const glm::vec3& root, float dt);
    /// Horizontal travel of the feet while in contact (m), over the whole recording.
    [[nodiscard]] float skate_m(const ContactThresholds& t = {}) const;
    /// Horizontal distance the root travelled (m).
    [[nodiscard]] float walked_m() const { return walked_; }
    /// Skate in mm per metre walked (0 when the root did not travel 1 cm).
    [[nodiscard]] float mm_per_metre(const ContactThresholds& t = {}) const;
    /// Frames recorded.
    [[nodiscard]] size_t frames() const { return dts_.size(); }

private:
    size_t feet_ = 0;
    std::vector<glm::vec3> positions_;  // frame-major
    std::vector<float> dts_;
    glm::vec3 last_root_{0.0f};
    float walked_ = 0.0f;
};

/// Pops: per frame, the largest distance any joint moved since the previous frame, split into
/// ordinary frames and switch frames (the animation level, method or update interval changed).
class PopMeter {
public:
    /// Records one frame of world joint positions (same joints every frame); `switch_frame` marks a
    /// frame whose animation changed level or method since the previous one.
    void add(std::span<const glm::vec3> joints, bool switch_frame);
    /// 95th percentile of the ordinary frames' largest joint motion (m); 0 without ordinary frames.
    [[nodiscard]] float ordinary_p95() const;
    /// Largest joint motion of any ordinary frame (m); 0 without ordinary frames.
    [[nodiscard]] float ordinary_max() const;
    /// Largest joint motion on a switch frame (m); 0 without switch frames.
    [[nodiscard]] float worst_switch() const { return worst_switch_; }
    /// Switch frames seen.
    [[nodiscard]] size_t switches() const { return switches_; }

private:
    std::vector<glm::vec3> last_;
    std::vector<float> ordinary_;
    float worst_switch_ = 0.0f;
    size_t switches_ = 0;
};

}  // namespace aloha
