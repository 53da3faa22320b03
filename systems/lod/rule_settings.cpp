// The file-wide sections of a rule file: tiers (with optional hardware requirements), default_tier
// (a name or "auto"), hysteresis, budget (single total or animation/geometry parts), significance
// (an expression whose errors carry the file's line and column), and the level-cap checks.
#include "systems/lod/rule_parse_helpers.hpp"

#include "engine/core/text_position.hpp"

namespace aloha::lod_detail {

using nlohmann::json;

namespace {

void parse_tiers(JsonObjectReader& root, RuleFile& in, RuleTable& table) {
    if (const json* t = root.child("tiers")) {
        if (!t->is_array() || t->empty()) in.err("/tiers", "expected a non-empty array of tier names");
        for (size_t i = 0; t->is_array() && i < t->size(); ++i) {
            const std::string p = "/tiers/" + std::to_string(i);
            const json& item = (*t)[i];
            TierRequirements req;
            std::string name;
            if (item.is_object()) {  // {"name", "min_cores", "min_gpu_memory_mb", "needs_hardware_gpu"}
                JsonObjectReader r = in.object(item, p);
                r.allow({"description"});
                name = r.string("name", "", true);
                r.read("min_cores", req.min_cores, 0, 4096);
                r.read("min_gpu_memory_mb", req.min_gpu_memory_mb, 0, 1 << 30);
                req.needs_hardware_gpu = r.boolean("needs_hardware_gpu", req.needs_hardware_gpu);
                r.reject_unknown_keys();
                table.tier_requirements_given = true;
            } else if (item.is_string()) {
                name = item.get<std::string>();
            } else {
                in.err(p, "expected a tier name (string) or {name, min_cores, min_gpu_memory_mb, needs_hardware_gpu}");
                continue;
            }
            if (name.empty()) continue;
            if (table.find_tier(name) >= 0) in.err(p, "duplicate tier \"" + name + "\"");
            else table.tiers.push_back(name), table.tier_requirements.push_back(req);
        }
    }
    if (table.tiers.empty()) table.tiers.push_back("default"), table.tier_requirements.emplace_back();
    if (const json* d = root.child("default_tier")) {
        if (d->is_string() && d->get<std::string>() == "auto") {
            table.tier_auto = true;  // the host picks; without hardware facts the richest tier
            table.default_tier = static_cast<uint8_t>(table.tiers.size() - 1);
        } else {
            const int t = d->is_string() ? table.find_tier(d->get<std::string>()) : -1;
            if (t < 0) in.err("/default_tier", "unknown tier " + d->dump() + " (declare it in \"tiers\", or write \"auto\")");
            else table.default_tier = static_cast<uint8_t>(t);
        }
    }
}

void parse_budget_part(JsonObjectReader& b, const char* key, RuleFile& in, BudgetPartParams* part) {
    const json* j = b.child(key);
    if (!j) return;
    const std::string p = std::string("/budget/") + key;
    if (!j->is_object()) return in.err(p, "expected an object {target_ms, tolerance, gain, max_demotion, react_tolerance}");
    JsonObjectReader r = in.object(*j, p);
    r.allow({"description"});
    part->target_ms = static_cast<float>(r.number("target_ms", part->target_ms, 0.001, 10000.0, /*required=*/true));
    r.read("tolerance", part->tolerance, 0.0, 0.5);
    r.read("gain", part->gain, 0.01, 1.0);
    r.read("max_demotion", part->max_demotion, 0, 255);
    r.read("react_tolerance", part->react_tolerance, 0.0, 0.9);
    r.reject_unknown_keys();
}

void parse_budget(const json& value, RuleFile& in, RuleTable& table) {
    if (!value.is_object()) return in.err("/budget", "expected an object {target_ms | animation, geometry, ...}");
    JsonObjectReader b = in.object(value, "/budget");
    BudgetParams bp;
    b.allow({"description"});
    bp.enabled = b.boolean("enabled", bp.enabled);
    b.read("target_ms", bp.target_ms, 0.01, 10000.0);
    b.read("deadband", bp.deadband, 0.0, 0.9);
    b.read("smoothing", bp.smoothing, 0.001, 1.0);
    b.read("demote_gain", bp.demote_gain, 0.0, 1.0);
    b.read("promote_gain", bp.promote_gain, 0.0, 1.0);
    b.read("settle_frames", bp.settle_frames, 0, 1000);
    b.read("max_demotion", bp.max_demotion, 0, 255);
    b.read("cost_smoothing", bp.cost_smoothing, 0.001, 1.0);
    b.read("trim_smoothing", bp.trim_smoothing, 0.0, 1.0);
    b.read("dwell", bp.dwell, 0.0, 10.0);
    b.read("confidence", bp.confidence, 0.0, 10.0);
    bp.animation.max_demotion = bp.geometry.max_demotion = bp.max_demotion;
    parse_budget_part(b, "animation", in, &bp.animation);
    parse_budget_part(b, "geometry", in, &bp.geometry);
    b.reject_unknown_keys();
    const bool parts = value.contains("animation") || value.contains("geometry");
    if (parts && value.contains("target_ms"))
        in.err("/budget/target_ms", "give either one total 'target_ms' or the parts 'animation'/'geometry', not both");
    if (!parts && !value.contains("target_ms"))
        in.err("/budget", "missing 'target_ms' (one total) or 'animation'/'geometry' parts with their own target_ms");
    table.budget = bp;
}

void parse_significance(JsonObjectReader& root, std::string_view text, RuleTable& table) {
    const json* v = root.child("significance");
    if (!v) return;
    if (!v->is_string()) return root.error("significance", std::string("expected an expression string, got ") + v->type_name());
    ExprError e;
    if (table.significance.compile(v->get<std::string>(), &e)) return;
    int line = 0, column = 0;
    const size_t start = find_top_level_string(text, "significance");
    if (start != std::string_view::npos) line_column_of(text, raw_offset_in_string(text, start, e.offset), &line, &column);
    root.error_at(line, column, "significance", "significance expression, character " + std::to_string(e.offset + 1) + ": " + e.message);
}

}  // namespace

void parse_settings(JsonObjectReader& root, std::string_view text, RuleFile& in, RuleTable& table) {
    parse_tiers(root, in, table);
    if (const json* h = root.child("hysteresis")) {
        if (!h->is_object()) in.err("/hysteresis", "expected an object {band, min_seconds}");
        else {
            JsonObjectReader r = in.object(*h, "/hysteresis");
            r.allow({"description"});
            r.renamed("min_frames", "min_seconds", kSecondsNotFrames);
            r.read("band", table.hysteresis.band, 0.0, 0.9);
            r.read("min_seconds", table.hysteresis.min_seconds, 0.0, 600.0);
            r.reject_unknown_keys();
        }
    }
    if (const json* b = root.child("budget")) parse_budget(*b, in, table);
    parse_significance(root, text, table);
}

void check_caps(RuleFile& in, const RuleTable& table) {
    int last_shown = -1;  // the poorest geometric level that is drawn
    for (size_t l = 0; l < table.geom_levels.size(); ++l)
        if (table.geom_levels[l].method != GeomMethod::Hidden) last_shown = static_cast<int>(l);
    for (size_t l = 0; l < table.geom_levels.size(); ++l) {
        if (table.geom_levels[l].max_characters == kNoCap) continue;
        const std::string p = "/geometric_levels/" + std::to_string(l) + "/max_characters";
        if (table.geom_levels[l].method == GeomMethod::Hidden) in.err(p, "a hidden level cannot have a cap");
        else if (static_cast<int>(l) >= last_shown)
            in.err(p, "the poorest drawn level cannot have a cap: characters over it would have nowhere to go");
    }
    if (!table.anim_levels.empty() && table.anim_levels.back().max_characters != kNoCap)
        in.err("/animation_levels/" + std::to_string(table.anim_levels.size() - 1) + "/max_characters",
               "the poorest animation level cannot have a cap: characters over it would have nowhere to go");
}

}  // namespace aloha::lod_detail
