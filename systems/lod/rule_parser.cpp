// parse_rules: JSON text -> validated, compiled RuleTable. Every problem is reported with the file
// and either line/column (syntax) or JSON path (meaning); see docs/RULES.md for the error classes.
#include "systems/lod/rule_conditions.hpp"
#include "systems/lod/rule_parse_helpers.hpp"
#include "systems/lod/rule_table.hpp"

#include "engine/core/json_reader.hpp"

#include <nlohmann/json.hpp>

#include <cmath>
#include <set>

namespace aloha {
namespace {

using nlohmann::json;
using lod_detail::RawBox;
using lod_detail::RuleFile;

struct Parser {
    RuleFile in;
    RuleTable table;
    std::string_view text;

    void err(const std::string& path, std::string message) { in.err(path, std::move(message)); }

    void parse_geom_level(const json& j, const std::string& p) {
        GeomLevelDef d;
        if (!j.is_object()) return err(p, "expected an object describing a geometric level");
        JsonObjectReader r = in.object(j, p);
        d.name = r.string("name", "", true);
        r.allow({"description"});
        d.method = static_cast<GeomMethod>(
            r.choice("method", {"hidden", "rigid_proxy", "skinned_mesh", "layered", "subdivided", "impostor"}, 1, true));
        constexpr uint8_t kDefaultLayers[] = {0, kLayerSkeleton, kLayerSkeleton | kLayerSkin,
                                              kLayerSkeleton | kLayerMuscle | kLayerFat | kLayerSkin,
                                              kLayerSkeleton | kLayerMuscle | kLayerFat | kLayerSkin,
                                              kLayerSkeleton | kLayerSkin};  // impostor: the skin, baked
        d.layers = kDefaultLayers[static_cast<int>(d.method)];
        r.read("theta_steps", d.theta_steps, 3, 1024);
        r.read("phi_steps", d.phi_steps, 2, 1024);
        r.read("subdivision", d.subdiv_level, 0, 4);
        if (const json* l = r.child("layers")) {
            if (!l->is_array()) err(p + "/layers", "expected an array of layer names");
            d.layers = 0;
            for (size_t i = 0; l->is_array() && i < l->size(); ++i) {
                const std::string lp = p + "/layers/" + std::to_string(i);
                const json& item = (*l)[i];
                const std::string n = item.is_string() ? item.get<std::string>() : "";
                if (n == "skeleton") d.layers |= kLayerSkeleton;
                else if (n == "muscle") d.layers |= kLayerMuscle;
                else if (n == "fat") d.layers |= kLayerFat;
                else if (n == "skin") d.layers |= kLayerSkin;
                else err(lp, "unknown layer " + item.dump() + " (allowed: skeleton, muscle, fat, skin)");
            }
            // Each method draws a fixed set of layers; only the fat springs of the muscle methods can
            // be peeled off (skin at the springs' rest ends).
            const uint8_t all = kDefaultLayers[static_cast<int>(d.method)];
            const uint8_t needed = static_cast<uint8_t>(all & ~kLayerFat);
            if (l->is_array() && ((d.layers & needed) != needed || (d.layers & ~all) != 0))
                err(p + "/layers", all == needed ? "this method's layers are fixed: give its default or leave the key out"
                                                 : "layered and subdivided levels need skeleton, muscle and skin; fat is optional");
        }
        r.read("geomorph_s", d.geomorph_s, 0.0, 10.0);
        r.renamed("geomorph_frames", "geomorph_s", lod_detail::kSecondsNotFrames);
        r.read("enter_after_s", d.enter_after_s, 0.0, 600.0);
        r.read("max_characters", d.max_characters, 0, 1.0e9);
        r.read("simplify_error", d.simplify_error, 0.0, 0.25);
        r.reject_unknown_keys();
        if (d.method == GeomMethod::Subdivided && d.subdiv_level == 0)
            err(p + "/subdivision", "method 'subdivided' needs subdivision >= 1");
        if (d.simplify_error > 0.0f && d.method != GeomMethod::SkinnedMesh)
            err(p + "/simplify_error", "only a 'skinned_mesh' level can be simplified (the other methods build their own surfaces)");
        if (!d.name.empty() && table.find_geom_level(d.name) >= 0)
            err(p + "/name", "duplicate geometric level name '" + d.name + "'");
        table.geom_levels.push_back(std::move(d));
    }

    void parse_anim_level(const json& j, const std::string& p) {
        AnimLevelDef d;
        if (!j.is_object()) return err(p, "expected an object describing an animation level");
        JsonObjectReader r = in.object(j, p);
        d.name = r.string("name", "", true);
        r.allow({"description"});
        d.walk = static_cast<WalkMethod>(r.choice("walk", {"clip", "kinematic", "dynamic"}, 0, true));
        d.ik = static_cast<IkSolver>(r.choice("ik", {"none", "ccd", "dls"}, 0));
        if (d.ik != IkSolver::None) d.ik_iterations = 4;
        r.read("ik_iterations", d.ik_iterations, 0, 255);
        r.read("ik_tolerance", d.ik_tolerance, 1e-7, 1.0);
        r.read("update_interval", d.update_interval, 1, 255);
        r.read("crossfade_s", d.crossfade_s, 0.0, 10.0);
        r.renamed("crossfade_frames", "crossfade_s", lod_detail::kSecondsNotFrames);
        r.read("max_characters", d.max_characters, 0, 1.0e9);
        r.reject_unknown_keys();
        if (d.ik != IkSolver::None && d.ik_iterations == 0)
            err(p + "/ik_iterations", "an IK solver needs ik_iterations >= 1");
        if (!d.name.empty() && table.find_anim_level(d.name) >= 0)
            err(p + "/name", "duplicate animation level name '" + d.name + "'");
        table.anim_levels.push_back(std::move(d));
    }

    // Parses one rule; returns its compiled boxes through `boxes` (empty when the rule is broken).
    void parse_rule(const json& j, const std::string& p, std::vector<RawBox>* boxes) {
        RuleDef r;
        r.json_path = p;
        boxes->clear();
        if (!j.is_object()) return err(p, "expected a rule object {name, when, then}");
        JsonObjectReader rr = in.object(j, p);
        r.name = rr.string("name", "", true);
        rr.allow({"description", "when"});
        if (!r.name.empty() && table.find_rule(r.name) >= 0) err(p + "/name", "duplicate rule name '" + r.name + "'");
        const json* then = rr.child("then");
        rr.reject_unknown_keys();
        if (!then || !then->is_object()) {
            err(p, "missing 'then' object {\"geometry\": level, \"animation\": level}");
        } else {
            JsonObjectReader t = in.object(*then, p + "/then");
            const std::string g = t.string("geometry", "", true);
            const std::string a = t.string("animation", "", true);
            t.reject_unknown_keys();
            const int gi = table.find_geom_level(g);
            const int ai = table.find_anim_level(a);
            if (!g.empty() && gi < 0) err(p + "/then/geometry", "unknown geometric level '" + g + "'");
            if (!a.empty() && ai < 0) err(p + "/then/animation", "unknown animation level '" + a + "'");
            r.geom_level = static_cast<uint8_t>(std::max(gi, 0));
            r.anim_level = static_cast<uint8_t>(std::max(ai, 0));
        }
        lod_detail::ConditionContext ctx{&in.source, &table.tiers, &in.errors};
        static const json kAlways = json::object();
        const json& when = j.contains("when") ? j["when"] : kAlways;
        const size_t before = in.errors.size();
        if (lod_detail::compile_condition(when, p + "/when", ctx, boxes) && boxes->empty() &&
            in.errors.size() == before) {
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
        for (const RawBox& b : boxes) {
            ConditionBox cb;
            cb.lo = b.lo;
            cb.hi = b.hi;
            widen_box(cb, table.hysteresis.band);
            table.boxes.push_back(cb);
        }
        table.compiled.push_back(c);
    }

    void parse(const json& root) {
        if (!root.is_object()) return err("", "the rule file must be a JSON object");
        JsonObjectReader top = in.object(root, "");
        top.allow({"$schema", "description"});
        lod_detail::parse_settings(top, text, in, table);
        top.allow({"geometric_levels", "animation_levels", "rules"});
        top.reject_unknown_keys();
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
        lod_detail::check_caps(in, table);
        if (rl.is_array() && !rl.empty() && !table.rules.empty() && !table.rules.back().unconditional) {
            err("/rules/" + std::to_string(rl.size() - 1),
                "no fallback: the last rule must have no conditions so every character gets a level");
        }
        if (!in.errors.empty()) return;
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
                    in.source, "rule '" + table.rules[i].name + "' never fires: every case it covers is taken by rule '" +
                                table.rules[e].name + "' (/rules/" + std::to_string(e) + ") before it",
                    0, 0, p));
                return;
            }
        }
    }
};

}  // namespace

Result<RuleTable> parse_rules(std::string_view text, const std::string& source_name, std::vector<Error>* all_errors) {
    Parser parser;
    parser.in.source = source_name;
    parser.text = text;
    parser.table.source = source_name;
    auto parsed = parse_json_text(text, source_name, /*allow_comments=*/true);
    if (!parsed.ok()) {
        if (all_errors) all_errors->push_back(parsed.error());
        return parsed.error();
    }
    parser.parse(parsed.value());
    if (!parser.in.errors.empty()) {
        if (all_errors) all_errors->insert(all_errors->end(), parser.in.errors.begin(), parser.in.errors.end());
        return parser.in.errors.front();
    }
    return std::move(parser.table);
}

}  // namespace aloha
