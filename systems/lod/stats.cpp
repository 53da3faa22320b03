#include "systems/lod/stats.hpp"

#include "systems/lod/frame_budget.hpp"

#include <nlohmann/json.hpp>
#include <iterator>
#include <algorithm>

namespace aloha {

std::string_view to_string(GeomMethod m) {
    constexpr std::string_view names[] = {"hidden", "rigid_proxy", "skinned_mesh", "layered", "subdivided", "impostor"};
    const auto i = static_cast<size_t>(m);
    return i < std::size(names) ? names[i] : "?";
}

std::string_view to_string(WalkMethod m) {
    constexpr std::string_view names[] = {"clip", "kinematic", "dynamic"};
    const auto i = static_cast<size_t>(m);
    return i < 3 ? names[i] : "?";
}

std::string_view to_string(IkSolver s) {
    constexpr std::string_view names[] = {"none", "ccd", "dls"};
    const auto i = static_cast<size_t>(s);
    return i < 3 ? names[i] : "?";
}

bool LodStatsJob::Validate(std::vector<std::string>* errors) const {
    bool ok = true;
    auto fail = [&](std::string m) {
        ok = false;
        if (errors) errors->push_back("LodStatsJob: " + std::move(m));
    };
    if (table == nullptr || table->geom_levels.empty() || table->anim_levels.empty()) fail("needs a loaded rule table");
    if (output == nullptr) fail("needs an output LodStats");
    if (!attributes.empty() && attributes.size() != states.size()) fail("attributes size differs from states (and is not empty)");
    return ok;
}

void LodStatsJob::Run() const {
    LodStats& s = *output;
    const RuleTable& t = *table;
    s.per_geom_level.assign(t.geom_levels.size(), 0);
    s.per_anim_level.assign(t.anim_levels.size(), 0);
    s.per_rule.assign(t.rules.size(), 0);
    s.per_geom_method.fill(0);
    s.per_walk_method.fill(0);
    s.characters = static_cast<uint32_t>(states.size());
    s.visible = s.demoted = s.in_geomorph = s.in_crossfade = s.occluded = 0;
    s.occlusion_histogram.fill(0);
    const size_t last_geom = t.geom_levels.size() - 1;
    const size_t last_anim = t.anim_levels.size() - 1;
    for (size_t i = 0; i < states.size(); ++i) {
        const LodState& st = states[i];
        const size_t g = std::min<size_t>(st.geom_level, last_geom);
        const size_t a = std::min<size_t>(st.anim_level, last_anim);
        ++s.per_geom_level[g];
        ++s.per_anim_level[a];
        if (st.rule_id < s.per_rule.size()) ++s.per_rule[st.rule_id];
        ++s.per_geom_method[static_cast<size_t>(t.geom_levels[g].method)];
        ++s.per_walk_method[static_cast<size_t>(t.anim_levels[a].walk)];
        s.demoted += st.budget_demotion > 0 || st.anim_demotion > 0;
        if (!attributes.empty() && attributes[i].visible != 0) {
            const float o = attributes[i].occluded;
            s.occluded += o >= 1.0f;
            ++s.occlusion_histogram[o <= 0.0f ? 0 : o < 0.5f ? 1 : o < 0.9f ? 2 : o < 1.0f ? 3 : 4];
        }
        s.in_geomorph += st.geomorph_left_s > 0.0f;
        s.in_crossfade += st.crossfade_left_s > 0.0f;
        if (!attributes.empty()) s.visible += attributes[i].visible != 0;
    }
}

LodExplanation explain(const RuleTable& table, uint32_t i, std::span<const LodAttributes> attributes,
                       std::span<const LodState> states) {
    LodExplanation e;
    const LodState& s = states[i];
    e.index = i;
    e.attributes = attributes[i];
    e.noticeability = table.significance.evaluate(attributes[i]);
    e.rule_id = s.rule_id;
    if (s.rule_id < table.rules.size()) {
        const RuleDef& r = table.rules[s.rule_id];
        e.rule_name = r.name;
        e.rule_geom_level = r.geom_level;
        e.rule_anim_level = r.anim_level;
    }
    e.budget_demotion = s.budget_demotion;
    e.anim_demotion = s.anim_demotion;
    e.cap_geom_level = s.cap_geom_level;
    e.cap_anim_level = s.cap_anim_level;
    e.always_full = s.always_full != 0;
    e.geom = table.geom_lod(s.geom_level);
    e.geom_level_name = table.geom_levels[e.geom.level].name;
    e.anim = table.anim_lod(s.anim_level);
    e.anim_level_name = table.anim_levels[e.anim.level].name;
    e.prev_geom_level = s.prev_geom_level;
    e.geomorph_left_s = s.geomorph_left_s;
    e.prev_anim_level = s.prev_anim_level;
    e.crossfade_left_s = s.crossfade_left_s;
    e.seconds_at_geom = s.seconds_at_geom;
    e.seconds_at_anim = s.seconds_at_anim;
    return e;
}

nlohmann::json to_json(const LodExplanation& e) {
    using nlohmann::json;
    const LodAttributes& a = e.attributes;
    return json{
        {"index", e.index},
        {"attributes", {{"distance", a.distance}, {"projected_height_px", a.projected_height_px},
                        {"eccentricity", a.eccentricity}, {"speed", a.speed}, {"visible", a.visible != 0},
                        {"importance", a.importance}, {"occluded", a.occluded}}},
        {"noticeability", e.noticeability},
        {"rule", {{"id", e.rule_id}, {"name", e.rule_name}, {"geometry_level", e.rule_geom_level},
                  {"animation_level", e.rule_anim_level}}},
        {"budget_demotion", e.budget_demotion},
        {"anim_budget_demotion", e.anim_demotion},
        {"caps", {{"geometry_level", e.cap_geom_level}, {"animation_level", e.cap_anim_level}}},
        {"always_full", e.always_full},
        {"geometry", {{"level", e.geom.level}, {"name", e.geom_level_name}, {"method", to_string(e.geom.method)},
                      {"theta_steps", e.geom.theta_steps}, {"phi_steps", e.geom.phi_steps},
                      {"subdivision", e.geom.subdiv_level}, {"layers", e.geom.layers},
                      {"previous_level", e.prev_geom_level}, {"geomorph_left_s", e.geomorph_left_s},
                      {"seconds_at_level", e.seconds_at_geom}}},
        {"animation", {{"level", e.anim.level}, {"name", e.anim_level_name}, {"walk", to_string(e.anim.walk)},
                       {"ik", to_string(e.anim.ik)}, {"ik_iterations", e.anim.ik_iterations},
                       {"ik_tolerance", e.anim.ik_tolerance}, {"update_interval", e.anim.update_interval},
                       {"previous_level", e.prev_anim_level}, {"crossfade_left_s", e.crossfade_left_s},
                       {"seconds_at_level", e.seconds_at_anim}}},
    };
}

nlohmann::json to_json(const LodStats& s, const RuleTable& table) {
    using nlohmann::json;
    json geom = json::object();
    for (size_t i = 0; i < s.per_geom_level.size() && i < table.geom_levels.size(); ++i)
        geom[table.geom_levels[i].name] = s.per_geom_level[i];
    json anim = json::object();
    for (size_t i = 0; i < s.per_anim_level.size() && i < table.anim_levels.size(); ++i)
        anim[table.anim_levels[i].name] = s.per_anim_level[i];
    json rules = json::object();
    for (size_t i = 0; i < s.per_rule.size() && i < table.rules.size(); ++i) rules[table.rules[i].name] = s.per_rule[i];
    json gm = json::object();
    for (size_t i = 0; i < s.per_geom_method.size(); ++i) gm[std::string(to_string(static_cast<GeomMethod>(i)))] = s.per_geom_method[i];
    json wm = json::object();
    for (size_t i = 0; i < s.per_walk_method.size(); ++i) wm[std::string(to_string(static_cast<WalkMethod>(i)))] = s.per_walk_method[i];
    return json{{"characters", s.characters}, {"visible", s.visible},       {"demoted", s.demoted},
                {"occluded", s.occluded},       {"occlusion_histogram", s.occlusion_histogram},
                {"in_geomorph", s.in_geomorph}, {"in_crossfade", s.in_crossfade},
                {"geometry_levels", geom},      {"animation_levels", anim}, {"rules", rules},
                {"geometry_methods", gm},       {"walk_methods", wm}};
}

}  // namespace aloha
