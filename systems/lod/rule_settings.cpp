// The file-wide sections of a rule file: tiers (with optional hardware requirements), default_tier
// (a name or "auto"), hysteresis, budget (single total or animation/geometry parts), significance
// (an expression whose errors carry the file's line and column), and the level-cap checks.
#include "systems/lod/rule_parse_helpers.hpp"

#include "engine/core/text_position.hpp"

namespace aloha::lod_detail {

using nlohmann::json;

void JsonChecker::err(const std::string& path, std::string message) {
    errors.push_back(make_error(source, std::move(message), 0, 0, path));
}

void JsonChecker::err_at(int line, int column, const std::string& path, std::string message) {
    errors.push_back(make_error(source, std::move(message), line, column, path));
}

void JsonChecker::check_keys(const json& obj, const std::string& path, std::initializer_list<const char*> allowed) {
    for (const auto& [key, value] : obj.items()) {
        bool known = false;
        for (const char* a : allowed) known = known || key == a;
        if (!known) {
            std::string list;
            for (const char* a : allowed) list += std::string(list.empty() ? "" : ", ") + a;
            err(path + "/" + key, "unknown key '" + key + "' (allowed: " + list + ")");
        }
    }
}

void JsonChecker::renamed_key(const json& obj, const std::string& path, const char* old_key, const char* new_key) {
    if (obj.contains(old_key))
        err(path + "/" + old_key, std::string("'") + old_key + "' was replaced by '" + new_key +
                                      "' (seconds of simulated time, so the behaviour does not depend on the frame rate)");
}

bool JsonChecker::number_value(const json& obj, const char* key, const std::string& path, double lo, double hi,
                               bool integer, double* out) {
    if (!obj.contains(key)) return false;
    const json& v = obj[key];
    const std::string p = path + "/" + key;
    if (!v.is_number() || (integer && !v.is_number_integer())) {
        err(p, std::string("expected ") + (integer ? "an integer" : "a number") + ", got " + v.type_name());
        return false;
    }
    const double x = v.get<double>();
    if (!(x >= lo && x <= hi)) {
        err(p, "value " + v.dump() + " out of range [" + json(lo).dump() + ", " + json(hi).dump() + "]");
        return false;
    }
    *out = x;
    return true;
}

std::string JsonChecker::string(const json& obj, const char* key, const std::string& path) {
    if (!obj.contains(key)) {
        err(path, std::string("missing required key '") + key + "'");
        return {};
    }
    if (!obj[key].is_string() || obj[key].get<std::string>().empty()) {
        err(path + "/" + key, "expected a non-empty string");
        return {};
    }
    return obj[key].get<std::string>();
}

void JsonChecker::boolean(const json& obj, const char* key, const std::string& path, bool* out) {
    if (!obj.contains(key)) return;
    if (!obj[key].is_boolean()) return err(path + "/" + key, std::string("expected true or false, got ") + obj[key].type_name());
    *out = obj[key].get<bool>();
}

int JsonChecker::choice(const json& obj, const char* key, const std::string& path, std::initializer_list<const char*> names,
                        int fallback, bool required) {
    if (!obj.contains(key)) {
        if (required) err(path, std::string("missing required key '") + key + "'");
        return fallback;
    }
    std::string list;
    int i = 0;
    for (const char* n : names) {
        if (obj[key].is_string() && obj[key].get<std::string>() == n) return i;
        list += std::string(list.empty() ? "" : ", ") + n;
        ++i;
    }
    err(path + "/" + key, "unknown value " + obj[key].dump() + " (allowed: " + list + ")");
    return fallback;
}

namespace {

void parse_tiers(const json& root, JsonChecker& in, RuleTable& table) {
    if (root.contains("tiers")) {
        const json& t = root["tiers"];
        if (!t.is_array() || t.empty()) in.err("/tiers", "expected a non-empty array of tier names");
        for (size_t i = 0; t.is_array() && i < t.size(); ++i) {
            const std::string p = "/tiers/" + std::to_string(i);
            TierRequirements req;
            std::string name;
            if (t[i].is_object()) {  // {"name", "min_cores", "min_gpu_memory_mb", "needs_hardware_gpu"}
                in.check_keys(t[i], p, {"name", "description", "min_cores", "min_gpu_memory_mb", "needs_hardware_gpu"});
                name = in.string(t[i], "name", p);
                in.number(t[i], "min_cores", p, 0, 4096, true, &req.min_cores);
                in.number(t[i], "min_gpu_memory_mb", p, 0, 1 << 30, true, &req.min_gpu_memory_mb);
                in.boolean(t[i], "needs_hardware_gpu", p, &req.needs_hardware_gpu);
                table.tier_requirements_given = true;
            } else if (t[i].is_string()) {
                name = t[i].get<std::string>();
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
    if (root.contains("default_tier")) {
        const json& d = root["default_tier"];
        if (d.is_string() && d.get<std::string>() == "auto") {
            table.tier_auto = true;  // the host picks; without hardware facts the richest tier
            table.default_tier = static_cast<uint8_t>(table.tiers.size() - 1);
        } else {
            const int t = d.is_string() ? table.find_tier(d.get<std::string>()) : -1;
            if (t < 0) in.err("/default_tier", "unknown tier " + d.dump() + " (declare it in \"tiers\", or write \"auto\")");
            else table.default_tier = static_cast<uint8_t>(t);
        }
    }
}

void parse_budget_part(const json& b, const char* key, JsonChecker& in, BudgetPartParams* part) {
    if (!b.contains(key)) return;
    const std::string p = std::string("/budget/") + key;
    const json& j = b[key];
    if (!j.is_object()) return in.err(p, "expected an object {target_ms, tolerance, gain, max_demotion}");
    in.check_keys(j, p, {"description", "target_ms", "tolerance", "gain", "max_demotion"});
    if (!j.contains("target_ms")) in.err(p, "missing required key 'target_ms'");
    in.number(j, "target_ms", p, 0.001, 10000.0, false, &part->target_ms);
    in.number(j, "tolerance", p, 0.0, 0.5, false, &part->tolerance);
    in.number(j, "gain", p, 0.01, 1.0, false, &part->gain);
    in.number(j, "max_demotion", p, 0, 255, true, &part->max_demotion);
}

void parse_budget(const json& b, JsonChecker& in, RuleTable& table) {
    if (!b.is_object()) return in.err("/budget", "expected an object {target_ms | animation, geometry, ...}");
    BudgetParams bp;
    in.check_keys(b, "/budget", {"description", "enabled", "target_ms", "deadband", "smoothing", "demote_gain",
                                 "promote_gain", "settle_frames", "max_demotion", "cost_smoothing", "animation",
                                 "geometry"});
    in.boolean(b, "enabled", "/budget", &bp.enabled);
    in.number(b, "target_ms", "/budget", 0.01, 10000.0, false, &bp.target_ms);
    in.number(b, "deadband", "/budget", 0.0, 0.9, false, &bp.deadband);
    in.number(b, "smoothing", "/budget", 0.001, 1.0, false, &bp.smoothing);
    in.number(b, "demote_gain", "/budget", 0.0, 1.0, false, &bp.demote_gain);
    in.number(b, "promote_gain", "/budget", 0.0, 1.0, false, &bp.promote_gain);
    in.number(b, "settle_frames", "/budget", 0, 1000, true, &bp.settle_frames);
    in.number(b, "max_demotion", "/budget", 0, 255, true, &bp.max_demotion);
    in.number(b, "cost_smoothing", "/budget", 0.001, 1.0, false, &bp.cost_smoothing);
    bp.animation.max_demotion = bp.geometry.max_demotion = bp.max_demotion;
    parse_budget_part(b, "animation", in, &bp.animation);
    parse_budget_part(b, "geometry", in, &bp.geometry);
    const bool parts = b.contains("animation") || b.contains("geometry");
    if (parts && b.contains("target_ms"))
        in.err("/budget/target_ms", "give either one total 'target_ms' or the parts 'animation'/'geometry', not both");
    if (!parts && !b.contains("target_ms"))
        in.err("/budget", "missing 'target_ms' (one total) or 'animation'/'geometry' parts with their own target_ms");
    table.budget = bp;
}

void parse_significance(const json& root, std::string_view text, JsonChecker& in, RuleTable& table) {
    if (!root.contains("significance")) return;
    const json& v = root["significance"];
    if (!v.is_string()) return in.err("/significance", std::string("expected an expression string, got ") + v.type_name());
    ExprError e;
    if (table.significance.compile(v.get<std::string>(), &e)) return;
    int line = 0, column = 0;
    const size_t start = find_top_level_string(text, "significance");
    if (start != std::string_view::npos) line_column_of(text, raw_offset_in_string(text, start, e.offset), &line, &column);
    in.err_at(line, column, "/significance",
              "significance expression, character " + std::to_string(e.offset + 1) + ": " + e.message);
}

}  // namespace

void parse_settings(const json& root, std::string_view text, JsonChecker& in, RuleTable& table) {
    parse_tiers(root, in, table);
    if (root.contains("hysteresis")) {
        const json& h = root["hysteresis"];
        if (!h.is_object()) in.err("/hysteresis", "expected an object {band, min_seconds}");
        else {
            in.check_keys(h, "/hysteresis", {"description", "band", "min_seconds", "min_frames"});
            in.renamed_key(h, "/hysteresis", "min_frames", "min_seconds");
            in.number(h, "band", "/hysteresis", 0.0, 0.9, false, &table.hysteresis.band);
            in.number(h, "min_seconds", "/hysteresis", 0.0, 600.0, false, &table.hysteresis.min_seconds);
        }
    }
    if (root.contains("budget")) parse_budget(root["budget"], in, table);
    parse_significance(root, text, in, table);
}

void check_caps(JsonChecker& in, const RuleTable& table) {
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
