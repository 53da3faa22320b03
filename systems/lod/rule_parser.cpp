// parse_rules: JSON text -> validated, compiled RuleTable. Every problem is reported with the file
// and either line/column (syntax) or JSON path (meaning); see docs/RULES.md for the error classes.
#include "systems/lod/rule_conditions.hpp"
#include "systems/lod/rule_table.hpp"

#include "engine/core/json_depth.hpp"

#include <nlohmann/json.hpp>

#include <cmath>
#include <initializer_list>
#include <set>

namespace aloha {
namespace {

using nlohmann::json;
using lod_detail::RawBox;

struct Parser {
    std::string source;
    std::vector<Error> errors;
    RuleTable table;

    void err(const std::string& path, std::string message) {
        errors.push_back(make_error(source, std::move(message), 0, 0, path));
    }

    // Reports keys of `obj` not in `allowed` (typos are errors, not silently ignored).
    void check_keys(const json& obj, const std::string& path, std::initializer_list<const char*> allowed) {
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

    // Optional number in [lo, hi] (integer when `integer`); missing keeps *out.
    template <class T>
    void number(const json& obj, const char* key, const std::string& path, double lo, double hi, bool integer,
                T* out) {
        if (!obj.contains(key)) return;
        const json& v = obj[key];
        const std::string p = path + "/" + key;
        if (!v.is_number() || (integer && !v.is_number_integer())) {
            err(p, std::string("expected ") + (integer ? "an integer" : "a number") + ", got " + v.type_name());
            return;
        }
        const double x = v.get<double>();
        if (!(x >= lo && x <= hi)) {
            err(p, "value " + v.dump() + " out of range [" + json(lo).dump() + ", " + json(hi).dump() + "]");
            return;
        }
        *out = static_cast<T>(x);
    }

    // Required string member; returns "" (and reports) when missing or not a string.
    std::string string(const json& obj, const char* key, const std::string& path) {
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

    // Maps `value` through `names` (index = enum value); reports unknown names.
    int choice(const json& obj, const char* key, const std::string& path, std::initializer_list<const char*> names,
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

    void parse_geom_level(const json& j, const std::string& p) {
        GeomLevelDef d;
        if (!j.is_object()) return err(p, "expected an object describing a geometric level");
        check_keys(j, p, {"name", "description", "method", "theta_steps", "phi_steps", "subdivision", "layers",
                          "geomorph_frames"});
        d.name = string(j, "name", p);
        d.method = static_cast<GeomMethod>(
            choice(j, "method", p, {"hidden", "rigid_proxy", "skinned_mesh", "layered", "subdivided"}, 1, true));
        constexpr uint8_t kDefaultLayers[] = {0, kLayerSkeleton, kLayerSkeleton | kLayerSkin,
                                              kLayerSkeleton | kLayerMuscle | kLayerFat | kLayerSkin,
                                              kLayerSkeleton | kLayerMuscle | kLayerFat | kLayerSkin};
        d.layers = kDefaultLayers[static_cast<int>(d.method)];
        number(j, "theta_steps", p, 3, 1024, true, &d.theta_steps);
        number(j, "phi_steps", p, 2, 1024, true, &d.phi_steps);
        number(j, "subdivision", p, 0, 4, true, &d.subdiv_level);
        number(j, "geomorph_frames", p, 0, 600, true, &d.geomorph_frames);
        if (j.contains("layers")) {
            const json& l = j["layers"];
            if (!l.is_array()) err(p + "/layers", "expected an array of layer names");
            d.layers = 0;
            for (size_t i = 0; l.is_array() && i < l.size(); ++i) {
                const std::string lp = p + "/layers/" + std::to_string(i);
                const std::string n = l[i].is_string() ? l[i].get<std::string>() : "";
                if (n == "skeleton") d.layers |= kLayerSkeleton;
                else if (n == "muscle") d.layers |= kLayerMuscle;
                else if (n == "fat") d.layers |= kLayerFat;
                else if (n == "skin") d.layers |= kLayerSkin;
                else err(lp, "unknown layer " + l[i].dump() + " (allowed: skeleton, muscle, fat, skin)");
            }
        }
        if (d.method == GeomMethod::Subdivided && d.subdiv_level == 0)
            err(p + "/subdivision", "method 'subdivided' needs subdivision >= 1");
        if (!d.name.empty() && table.find_geom_level(d.name) >= 0)
            err(p + "/name", "duplicate geometric level name '" + d.name + "'");
        table.geom_levels.push_back(std::move(d));
    }

    void parse_anim_level(const json& j, const std::string& p) {
        AnimLevelDef d;
        if (!j.is_object()) return err(p, "expected an object describing an animation level");
        check_keys(j, p, {"name", "description", "walk", "ik", "ik_iterations", "ik_tolerance", "update_interval",
                          "crossfade_frames"});
        d.name = string(j, "name", p);
        d.walk = static_cast<WalkMethod>(choice(j, "walk", p, {"clip", "kinematic", "dynamic"}, 0, true));
        d.ik = static_cast<IkSolver>(choice(j, "ik", p, {"none", "ccd", "dls"}, 0, false));
        if (d.ik != IkSolver::None) d.ik_iterations = 4;
        number(j, "ik_iterations", p, 0, 255, true, &d.ik_iterations);
        number(j, "ik_tolerance", p, 1e-7, 1.0, false, &d.ik_tolerance);
        number(j, "update_interval", p, 1, 255, true, &d.update_interval);
        number(j, "crossfade_frames", p, 0, 255, true, &d.crossfade_frames);
        if (d.ik != IkSolver::None && d.ik_iterations == 0)
            err(p + "/ik_iterations", "an IK solver needs ik_iterations >= 1");
        if (!d.name.empty() && table.find_anim_level(d.name) >= 0)
            err(p + "/name", "duplicate animation level name '" + d.name + "'");
        table.anim_levels.push_back(std::move(d));
    }

    void parse_settings(const json& root) {
        if (root.contains("tiers")) {
            const json& t = root["tiers"];
            if (!t.is_array() || t.empty()) err("/tiers", "expected a non-empty array of tier names");
            for (size_t i = 0; t.is_array() && i < t.size(); ++i) {
                const std::string p = "/tiers/" + std::to_string(i);
                if (!t[i].is_string()) err(p, "expected a tier name (string)");
                else if (table.find_tier(t[i].get<std::string>()) >= 0) err(p, "duplicate tier " + t[i].dump());
                else table.tiers.push_back(t[i].get<std::string>());
            }
        }
        if (table.tiers.empty()) table.tiers.push_back("default");
        if (root.contains("default_tier")) {
            const json& d = root["default_tier"];
            const int t = d.is_string() ? table.find_tier(d.get<std::string>()) : -1;
            if (t < 0) err("/default_tier", "unknown tier " + d.dump() + " (declare it in \"tiers\")");
            else table.default_tier = static_cast<uint8_t>(t);
        }
        if (root.contains("hysteresis")) {
            const json& h = root["hysteresis"];
            if (!h.is_object()) err("/hysteresis", "expected an object {band, min_frames}");
            else {
                check_keys(h, "/hysteresis", {"description", "band", "min_frames"});
                number(h, "band", "/hysteresis", 0.0, 0.9, false, &table.hysteresis.band);
                number(h, "min_frames", "/hysteresis", 0, 65535, true, &table.hysteresis.min_frames);
            }
        }
        if (root.contains("budget")) {
            const json& b = root["budget"];
            if (!b.is_object()) return err("/budget", "expected an object {target_ms, ...}");
            BudgetParams bp;
            check_keys(b, "/budget", {"description", "target_ms", "deadband", "smoothing", "demote_gain",
                                      "promote_gain", "settle_frames", "max_demotion"});
            if (!b.contains("target_ms")) err("/budget", "missing required key 'target_ms'");
            number(b, "target_ms", "/budget", 0.01, 10000.0, false, &bp.target_ms);
            number(b, "deadband", "/budget", 0.0, 0.9, false, &bp.deadband);
            number(b, "smoothing", "/budget", 0.001, 1.0, false, &bp.smoothing);
            number(b, "demote_gain", "/budget", 0.0, 1.0, false, &bp.demote_gain);
            number(b, "promote_gain", "/budget", 0.0, 1.0, false, &bp.promote_gain);
            number(b, "settle_frames", "/budget", 0, 1000, true, &bp.settle_frames);
            number(b, "max_demotion", "/budget", 0, 255, true, &bp.max_demotion);
            table.budget = bp;
        }
    }

    // Parses one rule; returns its compiled boxes through `boxes` (empty when the rule is broken).
    void parse_rule(const json& j, const std::string& p, std::vector<RawBox>* boxes) {
        RuleDef r;
        r.json_path = p;
        boxes->clear();
        if (!j.is_object()) return err(p, "expected a rule object {name, when, then}");
        check_keys(j, p, {"name", "description", "when", "then"});
        r.name = string(j, "name", p);
        if (!r.name.empty() && table.find_rule(r.name) >= 0) err(p + "/name", "duplicate rule name '" + r.name + "'");
        if (!j.contains("then") || !j["then"].is_object()) {
            err(p, "missing 'then' object {\"geometry\": level, \"animation\": level}");
        } else {
            const json& t = j["then"];
            check_keys(t, p + "/then", {"geometry", "animation"});
            const std::string g = string(t, "geometry", p + "/then");
            const std::string a = string(t, "animation", p + "/then");
            const int gi = table.find_geom_level(g);
            const int ai = table.find_anim_level(a);
            if (!g.empty() && gi < 0) err(p + "/then/geometry", "unknown geometric level '" + g + "'");
            if (!a.empty() && ai < 0) err(p + "/then/animation", "unknown animation level '" + a + "'");
            r.geom_level = static_cast<uint8_t>(std::max(gi, 0));
            r.anim_level = static_cast<uint8_t>(std::max(ai, 0));
        }
        lod_detail::ConditionContext ctx{&source, &table.tiers, &errors};
        static const json kAlways = json::object();
        const json& when = j.contains("when") ? j["when"] : kAlways;
        const size_t before = errors.size();
        if (lod_detail::compile_condition(when, p + "/when", ctx, boxes) && boxes->empty() &&
            errors.size() == before) {
            err(p + "/when", "unreachable rule: its conditions can never all be true");
        }
        r.unconditional = boxes->size() == 1 && lod_detail::box_full((*boxes)[0]);
        table.rules.push_back(std::move(r));
    }

    void compile_rule(const std::vector<RawBox>& boxes, size_t rule_index) {
        CompiledRule c;
        c.first_box = static_cast<uint32_t>(table.boxes.size());
        c.box_count = static_cast<uint32_t>(boxes.size());
        c.geom_level = table.rules[rule_index].geom_level;
        c.anim_level = table.rules[rule_index].anim_level;
        const float band = table.hysteresis.band;
        for (const RawBox& b : boxes) {
            ConditionBox cb;
            cb.lo = b.lo;
            cb.hi = b.hi;
            cb.lo_wide = b.lo;
            cb.hi_wide = b.hi;
            for (int k = 0; k < kLodAttributeCount; ++k) {
                const auto a = static_cast<LodAttribute>(k);
                if (a == LodAttribute::Visible || a == LodAttribute::Tier) continue;  // discrete: no band
                if (std::isfinite(b.lo[k])) cb.lo_wide[k] = b.lo[k] - band * std::fabs(b.lo[k]);
                if (std::isfinite(b.hi[k])) cb.hi_wide[k] = b.hi[k] + band * std::fabs(b.hi[k]);
            }
            table.boxes.push_back(cb);
        }
        table.compiled.push_back(c);
    }

    void parse(const json& root) {
        if (!root.is_object()) return err("", "the rule file must be a JSON object");
        check_keys(root, "", {"$schema", "description", "tiers", "default_tier", "hysteresis", "budget",
                              "geometric_levels", "animation_levels", "rules"});
        parse_settings(root);
        for (const char* key : {"geometric_levels", "animation_levels", "rules"}) {
            if (!root.contains(key) || !root[key].is_array() || root[key].empty())
                err("/" + std::string(key), "missing or empty array '" + std::string(key) + "'");
        }
        const json empty = json::array();
        const json& gl = root.contains("geometric_levels") ? root["geometric_levels"] : empty;
        const json& al = root.contains("animation_levels") ? root["animation_levels"] : empty;
        const json& rl = root.contains("rules") ? root["rules"] : empty;
        if (gl.size() > 255 || al.size() > 255) err("", "at most 255 levels of each kind");
        if (rl.size() > 65535) err("/rules", "at most 65535 rules");
        for (size_t i = 0; gl.is_array() && i < gl.size(); ++i) parse_geom_level(gl[i], "/geometric_levels/" + std::to_string(i));
        for (size_t i = 0; al.is_array() && i < al.size(); ++i) parse_anim_level(al[i], "/animation_levels/" + std::to_string(i));
        std::vector<std::vector<RawBox>> all_boxes;
        int first_unconditional = -1;
        for (size_t i = 0; rl.is_array() && i < rl.size(); ++i) {
            const std::string p = "/rules/" + std::to_string(i);
            all_boxes.emplace_back();
            parse_rule(rl[i], p, &all_boxes.back());
            const RuleDef& r = table.rules.back();
            if (first_unconditional >= 0) {
                err(p, "unreachable rule '" + r.name + "': rule '" + table.rules[first_unconditional].name +
                           "' (/rules/" + std::to_string(first_unconditional) +
                           ") before it has no conditions and always fires");
            } else if (r.unconditional) {
                first_unconditional = static_cast<int>(i);
            } else {
                check_shadowed(all_boxes, i, p);
            }
        }
        if (rl.is_array() && !rl.empty() && !table.rules.empty() && !table.rules.back().unconditional) {
            err("/rules/" + std::to_string(rl.size() - 1),
                "no fallback: the last rule must have no conditions so every character gets a level");
        }
        if (!errors.empty()) return;
        for (size_t i = 0; i < table.rules.size(); ++i) compile_rule(all_boxes[i], i);
    }

    // Warns when every alternative of rule `i` lies inside one alternative of an earlier rule.
    void check_shadowed(const std::vector<std::vector<RawBox>>& all, size_t i, const std::string& p) {
        if (all[i].empty()) return;
        for (size_t e = 0; e < i; ++e) {
            bool covered = true;
            for (const RawBox& b : all[i]) {
                bool in_one = false;
                for (const RawBox& o : all[e]) in_one = in_one || lod_detail::box_contains(o, b);
                covered = covered && in_one;
            }
            if (covered) {
                table.warnings.push_back(make_error(
                    source, "rule '" + table.rules[i].name + "' never fires: every case it covers is taken by rule '" +
                                table.rules[e].name + "' (/rules/" + std::to_string(e) + ") before it",
                    0, 0, p));
                return;
            }
        }
    }
};

// Converts nlohmann's byte count (1-based index of the byte it stopped at) to line/column.
void byte_to_line_column(std::string_view text, size_t byte, int* line, int* column) {
    const size_t end = std::min(byte == 0 ? 0 : byte - 1, text.size());
    *line = 1;
    size_t line_start = 0;
    for (size_t i = 0; i < end; ++i) {
        if (text[i] == '\n') {
            ++*line;
            line_start = i + 1;
        }
    }
    *column = static_cast<int>(end - line_start) + 1;
}

}  // namespace

Result<RuleTable> parse_rules(std::string_view text, const std::string& source_name, std::vector<Error>* all_errors) {
    Parser parser;
    parser.source = source_name;
    parser.table.source = source_name;
    json root;
    if (Status deep = check_json_depth(text, source_name); !deep.ok()) {
        if (all_errors) all_errors->push_back(deep.error());
        return deep.error();
    }
    try {
        root = json::parse(text.begin(), text.end(), nullptr, true, /*ignore_comments=*/true);
    } catch (const json::out_of_range& e) {  // e.g. 1e999: a number no double holds
        Error err = make_error(source_name, std::string("JSON number out of range: ") + e.what());
        if (all_errors) all_errors->push_back(err);
        return err;
    } catch (const json::parse_error& e) {
        int line = 0;
        int column = 0;
        byte_to_line_column(text, e.byte, &line, &column);
        std::string what = e.what();
        const size_t colon = what.find("syntax error");
        Error err = make_error(source_name, "JSON " + (colon == std::string::npos ? what : what.substr(colon)),
                               line, column);
        if (all_errors) all_errors->push_back(err);
        return err;
    }
    parser.parse(root);
    if (!parser.errors.empty()) {
        if (all_errors) all_errors->insert(all_errors->end(), parser.errors.begin(), parser.errors.end());
        return parser.errors.front();
    }
    return std::move(parser.table);
}

}  // namespace aloha
