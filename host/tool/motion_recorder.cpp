#include "host/tool/motion_recorder.hpp"

#include <cstdio>
#include <sstream>

namespace aloha::tool {

namespace {

std::string level_name(const RuleTable& table, uint8_t level) {
    return level < table.anim_levels.size() ? table.anim_levels[level].name : "level " + std::to_string(level);
}

nlohmann::json bucket_json(const MotionBucketFigures& b, float ordinary_p95_all) {
    return {{"frames", b.frames},
            {"walked_m", b.walked_m},
            {"skate_mm_per_m", b.mm_per_metre()},
            {"skate_ok", b.mm_per_metre() <= kSkateBarMmPerMetre},
            {"switch_frames", b.switch_frames},
            {"worst_switch_cm", 100.0 * b.worst_switch_m},
            {"pop_ok", b.worst_switch_m <= ordinary_p95_all},
            {"transition_frames", b.transition_frames},
            {"worst_transition_cm", 100.0 * b.worst_transition_m},
            {"ordinary_p95_cm", 100.0 * b.ordinary_p95_m},
            {"ordinary_max_cm", 100.0 * b.ordinary_max_m}};
}

}  // namespace

MotionRecorder::MotionRecorder(const World& world)
    : meter_(static_cast<uint32_t>(world.character_count())), last_(world.character_count()) {}

void MotionRecorder::record(const World& world, float dt) {
    for (uint32_t c = 0; c < last_.size(); ++c) {
        world.motion_sample(c, sample_);
        Last& l = last_[c];
        const bool changed = l.seen && (l.level != sample_.anim_level || l.interval != sample_.update_interval || l.method != sample_.method);
        const MotionFrameKind kind = changed ? MotionFrameKind::Switch
                                     : sample_.in_transition ? MotionFrameKind::Transition
                                                             : MotionFrameKind::Ordinary;
        meter_.add(c, sample_.joints, sample_.soles, sample_.root, dt, sample_.anim_level, sample_.update_interval, kind);
        l = Last{sample_.anim_level, sample_.update_interval, sample_.method, true};
    }
}

nlohmann::json MotionRecorder::report(const RuleTable& table) const {
    const MotionBucketFigures all = meter_.overall(contact_);
    nlohmann::json levels = nlohmann::json::array();
    bool skate_ok = true, pop_ok = true;
    for (const MotionBucketFigures& b : meter_.buckets(contact_)) {
        nlohmann::json j = bucket_json(b, all.ordinary_p95_m);
        j["anim_level"] = level_name(table, b.level);
        j["level_index"] = b.level;
        j["update_interval"] = b.interval;
        skate_ok = skate_ok && j["skate_ok"].get<bool>();
        pop_ok = pop_ok && j["pop_ok"].get<bool>();
        levels.push_back(std::move(j));
    }
    return {{"contact", {{"height_m", contact_.height}, {"speed_m_per_s", contact_.speed}}},
            {"skate_bar_mm_per_m", kSkateBarMmPerMetre},
            {"pop_bar", "worst switch-frame joint jump <= the 95th percentile of all ordinary frames"},
            {"overall", bucket_json(all, all.ordinary_p95_m)},
            {"per_level_and_interval", levels},
            {"skate_ok", skate_ok},
            {"pop_ok", pop_ok}};
}

std::string MotionRecorder::table(const RuleTable& table) const {
    const MotionBucketFigures all = meter_.overall(contact_);
    std::ostringstream out;
    char line[256];
    std::snprintf(line, sizeof line, "motion metrics (contact: within %.0f mm of the lowest height, under %.2f m/s)\n",
                  1000.0 * static_cast<double>(contact_.height), static_cast<double>(contact_.speed));
    out << line;
    std::snprintf(line, sizeof line, "%-16s %4s %9s %11s %9s %10s %12s %11s\n", "anim level", "int", "walked m",
                  "skate mm/m", "switches", "worst cm", "ord. p95 cm", "transit. cm");
    out << line;
    auto row = [&](const std::string& name, const std::string& interval, const MotionBucketFigures& b) {
        std::snprintf(line, sizeof line, "%-16s %4s %9.1f %7.2f %-3s %9llu %10.2f %12.2f %11.2f\n", name.c_str(),
                      interval.c_str(), b.walked_m, b.mm_per_metre(), b.mm_per_metre() <= kSkateBarMmPerMetre ? "ok" : "!!",
                      static_cast<unsigned long long>(b.switch_frames), 100.0 * static_cast<double>(b.worst_switch_m),
                      100.0 * static_cast<double>(b.ordinary_p95_m), 100.0 * static_cast<double>(b.worst_transition_m));
        out << line;
    };
    for (const MotionBucketFigures& b : meter_.buckets(contact_)) row(level_name(table, b.level), std::to_string(b.interval), b);
    row("all", "", all);
    std::snprintf(line, sizeof line, "pops: worst switch frame %.2f cm against the ordinary p95 %.2f cm: %s\n",
                  100.0 * static_cast<double>(all.worst_switch_m), 100.0 * static_cast<double>(all.ordinary_p95_m),
                  all.worst_switch_m <= all.ordinary_p95_m ? "ok" : "OVER");
    out << line;
    return out.str();
}

}  // namespace aloha::tool
