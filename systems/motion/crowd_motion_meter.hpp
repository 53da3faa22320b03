// Motion quality of a whole crowd, split per animation level and update interval: foot skate (the
// FootSkateMeter's measure, each step counted at the level the character was at) and pops (the
// PopMeter's measure: the largest joint jump on the frame of a change against the 95th percentile of
// ordinary frames; frames still blending a change in are kept apart from both).
#pragma once

#include "systems/motion/motion_metrics.hpp"

#include <glm/glm.hpp>

#include <cstdint>
#include <map>
#include <span>
#include <vector>

namespace aloha {

/// What a recorded frame was, for the pop measure.
enum class MotionFrameKind : uint8_t {
    Ordinary = 0,    ///< nothing changed and nothing is being blended in
    Switch = 1,      ///< the animation level, its update interval or the walk method changed this frame
    Transition = 2,  ///< a change made earlier is still being blended in
};

/// Figures of one (animation level, update interval) bucket.
struct MotionBucketFigures {
    uint8_t level = 0;
    uint8_t interval = 1;
    uint64_t frames = 0;          ///< character-frames recorded in the bucket
    double walked_m = 0.0;        ///< horizontal root travel (m)
    double skate_m = 0.0;         ///< horizontal sole travel while in contact (m)
    uint64_t switch_frames = 0;
    float worst_switch_m = 0.0f;  ///< largest joint jump on a switch frame (m)
    uint64_t transition_frames = 0;
    float worst_transition_m = 0.0f;  ///< largest joint motion on a transition frame (m)
    float ordinary_p95_m = 0.0f;  ///< 95th percentile of ordinary frames' largest joint motion (m)
    float ordinary_max_m = 0.0f;  ///< largest joint motion of any ordinary frame (m)
    /// Skate in mm per metre walked (0 below 1 cm of travel).
    [[nodiscard]] double mm_per_metre() const { return walked_m >= 0.01 ? 1000.0 * skate_m / walked_m : 0.0; }
};

/// Records every character's frames; figures at the end. Storage grows with characters x frames x
/// feet (one vec3 per foot per frame).
class CrowdMotionMeter {
public:
    /// For `characters` characters, numbered 0..characters-1.
    explicit CrowdMotionMeter(uint32_t characters);
    /// Records one frame of character `c`, `dt` seconds after its previous one: its world joints
    /// (same count every frame), world sole points (same count every frame; may be empty), root
    /// placement, the animation level and update interval in force, and the kind of frame.
    void add(uint32_t c, std::span<const glm::vec3> joints, std::span<const glm::vec3> soles, const glm::vec3& root,
             float dt, uint8_t level, uint8_t interval, MotionFrameKind kind);
    /// Figures per bucket, sorted by level then interval, with contact as `t` says.
    [[nodiscard]] std::vector<MotionBucketFigures> buckets(const ContactThresholds& t = {}) const;
    /// All buckets together (level and interval 0).
    [[nodiscard]] MotionBucketFigures overall(const ContactThresholds& t = {}) const;

private:
    struct Track {
        std::vector<glm::vec3> soles;   // frame-major
        std::vector<float> dts;
        std::vector<uint16_t> bucket;   // level << 8 | interval, per frame
        std::vector<float> walked;      // root travel since the previous frame
        std::vector<glm::vec3> last_joints;
        glm::vec3 last_root{0.0f};
        size_t feet = 0;
    };
    struct PopTally {
        std::vector<float> ordinary;
        uint64_t switches = 0, transitions = 0;
        float worst_switch = 0.0f, worst_transition = 0.0f;
    };
    std::vector<MotionBucketFigures> collect(const ContactThresholds& t, bool merged) const;

    std::vector<Track> tracks_;
    std::map<uint16_t, PopTally> pops_;  // by bucket key
};

}  // namespace aloha
