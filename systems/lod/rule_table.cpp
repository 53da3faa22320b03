#include "systems/lod/rule_table.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace aloha {

std::string_view attribute_name(LodAttribute a) {
    switch (a) {
        case LodAttribute::Distance: return "distance";
        case LodAttribute::ProjectedHeightPx: return "projected_height_px";
        case LodAttribute::Eccentricity: return "eccentricity";
        case LodAttribute::Speed: return "speed";
        case LodAttribute::Visible: return "visible";
        case LodAttribute::Importance: return "importance";
        case LodAttribute::Tier: return "tier";
        case LodAttribute::Occluded: return "occluded";
    }
    return "?";
}

namespace {
template <class T>
int find_named(const std::vector<T>& items, std::string_view name) {
    for (size_t i = 0; i < items.size(); ++i) {
        if (items[i].name == name) return static_cast<int>(i);
    }
    return -1;
}
}  // namespace

int RuleTable::find_geom_level(std::string_view name) const { return find_named(geom_levels, name); }

int RuleTable::find_anim_level(std::string_view name) const { return find_named(anim_levels, name); }

int RuleTable::find_rule(std::string_view name) const { return find_named(rules, name); }

int RuleTable::find_tier(std::string_view name) const {
    for (size_t i = 0; i < tiers.size(); ++i) {
        if (tiers[i] == name) return static_cast<int>(i);
    }
    return -1;
}

bool gets_value_band(LodAttribute a, float bound) {
    if (!std::isfinite(bound)) return false;
    switch (a) {
        case LodAttribute::Visible:
        case LodAttribute::Tier: return false;
        // `occluded` below 1 is an estimate that moves with the crowd: a band, as for the measured values.
        // A bound of 1 (certainly hidden) gets none: a character leaves `hidden` as soon as a part shows.
        case LodAttribute::Occluded: return bound > 0.0f && bound < 1.0f;
        default: return true;
    }
}

void widen_box(ConditionBox& box, float band) {
    box.lo_wide = box.lo;
    box.hi_wide = box.hi;
    for (int k = 0; k < kLodAttributeCount; ++k) {
        const auto a = static_cast<LodAttribute>(k);
        if (gets_value_band(a, box.lo[k])) box.lo_wide[k] = box.lo[k] - band * std::fabs(box.lo[k]);
        if (gets_value_band(a, box.hi[k])) box.hi_wide[k] = box.hi[k] + band * std::fabs(box.hi[k]);
        // A widened upper bound on `occluded` stays at most 1 (exclusive "lt" never admits the certainly hidden).
        if (a == LodAttribute::Occluded) box.hi_wide[k] = std::min(box.hi_wide[k], std::max(box.hi[k], 1.0f));
    }
}

bool RuleTable::has_caps() const {
    for (const auto& l : geom_levels)
        if (l.max_characters != kNoCap) return true;
    for (const auto& l : anim_levels)
        if (l.max_characters != kNoCap) return true;
    return false;
}

Result<RuleTable> load_rules(const std::string& path, std::vector<Error>* all_errors) {
    std::error_code ec;
    if (std::filesystem::is_directory(path, ec)) {
        Error e = make_error(path, "is a folder, not a regular file");
        if (all_errors) all_errors->push_back(e);
        return e;
    }
    std::ifstream in(path, std::ios::binary);
    if (!in) {
        Error e = make_error(path, "cannot open rule file for reading");
        if (all_errors) all_errors->push_back(e);
        return e;
    }
    std::ostringstream text;
    text << in.rdbuf();
    return parse_rules(text.str(), path, all_errors);
}

}  // namespace aloha
