#include "engine/assets/joint_limits.hpp"

#include "engine/core/json_reader.hpp"

#include "engine/assets/file_io.hpp"

#include <nlohmann/json.hpp>

#include <cmath>

namespace aloha {

namespace {

using nlohmann::json;

// One joint's {min, max} (angles in the file's units) into `limit` (radians); problems into `in`.
void read_joint(JsonObjectReader& r, float to_radians, double bound, JointLimit& limit) {
    limit.limited = true;
    const glm::vec3 lo = r.vec3("min", glm::vec3(0.0f), /*required=*/true, bound);
    const glm::vec3 hi = r.vec3("max", glm::vec3(0.0f), /*required=*/true, bound);
    r.reject_unknown_keys();
    limit.min_angles = lo * to_radians;
    limit.max_angles = hi * to_radians;
    for (int a = 0; a < 3; ++a)
        if (lo[a] > hi[a]) r.error("", std::string("min exceeds max on axis ") + "XYZ"[a]);
}

}  // namespace

Result<JointLimitTable> parse_joint_limits(std::string_view text, const std::string& source_name) {
    auto parsed = parse_json_text(text, source_name);
    if (!parsed.ok()) return parsed.error();
    std::vector<Error> errors;
    JsonObjectReader doc(parsed.value(), "", source_name, errors);
    doc.string("$schema", "");
    doc.string("description", "");
    const int units = doc.choice("units", {"degrees", "radians"}, 0);
    const float to_radians = units == 1 ? 1.0f : 3.14159265358979f / 180.0f;
    const double bound = units == 1 ? 3.14159265 : 180.0;
    doc.choice("euler_order", {"XYZ"}, 0);  // the only order supported
    JointLimitTable table;
    table.source = source_name;
    const json* joints = doc.child("joints");
    doc.reject_unknown_keys();
    if (doc.is_object() && !joints) doc.error("", "missing required key 'joints'");
    if (joints && !joints->is_object())
        doc.error("joints", std::string("expected an object keyed by joint name, got ") + joints->type_name());
    if (joints && joints->is_object()) {
        for (auto it = joints->begin(); it != joints->end(); ++it) {
            if (it.key().empty()) {
                doc.error("joints/", "empty joint name");
                continue;
            }
            JsonObjectReader r(it.value(), "/joints/" + it.key(), source_name, errors);
            JointLimit limit;
            read_joint(r, to_radians, bound, limit);
            table.names.push_back(it.key());
            table.limits.push_back(limit);
        }
    }
    if (!errors.empty()) return first_and_rest(errors);
    return table;
}

Result<JointLimitTable> load_joint_limits(const std::string& path) {
    Result<std::string> text = read_text_file(path);
    if (!text.ok()) return text.error();
    return parse_joint_limits(text.value(), path);
}

Status apply_joint_limits(Skeleton& skeleton, const JointLimitTable& table) {
    for (const std::string& name : table.names)
        if (skeleton.find(name) < 0)
            return make_error(table.source, "joint '" + name + "' is not in the skeleton", 0, 0, "/joints/" + name);
    return set_joint_limits(skeleton, table.names, table.limits, table.source);
}

Status apply_mapped_joint_limits(Skeleton& skeleton, const JointLimitTable& table, const HumanoidMap& map,
                                 const CanonicalFit& fit, std::vector<std::string>* skipped) {
    constexpr float kMaxTurn = 0.5235988f;  // 30 degrees
    std::vector<std::string> names;
    std::vector<JointLimit> limits;
    for (size_t i = 0; i < table.names.size(); ++i) {
        const int c = canonical_index(table.names[i]);
        if (c < 0) {
            if (skeleton.find(table.names[i]) < 0)
                return make_error(table.source, "joint limit for unknown joint '" + table.names[i] + "' (neither canonical nor in the skeleton)", 0, 0, "/joints/" + table.names[i]);
            names.push_back(table.names[i]);
            limits.push_back(table.limits[i]);
            continue;
        }
        const int j = map.joint[static_cast<size_t>(c)];
        const float turn = fit.bone_angle[static_cast<size_t>(c)];
        if (j < 0) continue;  // the skeleton has no such joint
        if (turn > kMaxTurn) {
            if (skipped) skipped->push_back(table.names[i] + " (" + std::to_string(static_cast<int>(std::lround(turn * 57.29578f))) + " degrees)");
        } else {
            names.push_back(skeleton.names()[static_cast<size_t>(j)]);
            limits.push_back(table.limits[i]);
        }
    }
    return set_joint_limits(skeleton, names, limits, table.source);
}

}  // namespace aloha
