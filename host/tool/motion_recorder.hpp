// Motion quality of a running World, frame by frame: each character's joints and soles fed to a
// CrowdMotionMeter with the frame classified as a change (animation level, update interval or method
// differs from the previous frame), a transition (a change still being blended in) or ordinary.
// `aloha profile --motion-metrics` reports it.
#pragma once

#include "host/scene/world.hpp"
#include "systems/lod/rule_table.hpp"
#include "systems/motion/crowd_motion_meter.hpp"

#include <nlohmann/json.hpp>

#include <string>
#include <vector>

namespace aloha::tool {

/// The skate bar: at most this many mm per metre walked at every level and update interval (the pop
/// bar is relative: no change-frame joint jump above the 95th percentile of ordinary frames).
inline constexpr double kSkateBarMmPerMetre = 10.0;

/// Records every character of a World after each step.
class MotionRecorder {
public:
    /// For the characters `world` has now (their count must not change while recording).
    explicit MotionRecorder(const World& world);
    /// Records the frame `world` just ran, `dt` seconds after the previous one.
    void record(const World& world, float dt);
    /// Figures per animation level and update interval, and overall, with the thresholds and the bars.
    [[nodiscard]] nlohmann::json report(const RuleTable& table) const;
    /// The same as a printed table.
    [[nodiscard]] std::string table(const RuleTable& table) const;

private:
    struct Last {
        uint8_t level = 0, interval = 0;
        std::string method;
        bool seen = false;
    };
    CrowdMotionMeter meter_;
    std::vector<Last> last_;
    MotionSample sample_;
    ContactThresholds contact_;
};

}  // namespace aloha::tool
