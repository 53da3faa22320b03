#include "engine/assets/joint_limits.hpp"

#include "engine/core/json_reader.hpp"

#include "engine/assets/file_io.hpp"

#include <nlohmann/json.hpp>

#include <cmath>

namespace aloha {

namespace {

using nlohmann::json;

std::string type_of(const json& v) { return v.type_name(); }

}  // namespace

Result<JointLimitTable> parse_joint_limits(std::string_view text, const std::string& source_name) {
    auto parsed = parse_json_text(text, source_name);
    if (!parsed.ok()) return parsed.error();
    const json& doc = parsed.value();
    auto fail = [&](const std::string& path, const std::string& msg) { return make_error(source_name, msg, 0, 0, path); };
    if (!doc.is_object()) return fail("", "top level must be an object, found " + type_of(doc));
    float to_radians = 3.14159265358979f / 180.0f;
    float bound = 180.0f;
    for (const auto& [key, value] : doc.items()) {
        if (key == "$schema" || key == "description") {
            if (!value.is_string()) return fail("/" + key, "must be a string, found " + type_of(value));
        } else if (key == "units") {
            if (value == "radians") {
                to_radians = 1.0f;
                bound = 3.14159265f;
            } else if (value != "degrees") {
                return fail("/units", "must be \"degrees\" or \"radians\", found " + value.dump());
            }
        } else if (key == "euler_order") {
            if (value != "XYZ") return fail("/euler_order", "only \"XYZ\" is supported, found " + value.dump());
        } else if (key != "joints") {
            return fail("/" + key, "unknown key (expected $schema, description, units, euler_order, joints)");
        }
    }
    if (!doc.contains("joints")) return fail("/joints", "missing");
    const json& joints = doc["joints"];
    if (!joints.is_object()) return fail("/joints", "must be an object keyed by joint name, found " + type_of(joints));
    JointLimitTable table;
    table.source = source_name;
    for (const auto& [name, entry] : joints.items()) {
        const std::string where = "/joints/" + name;
        if (name.empty()) return fail(where, "empty joint name");
        if (!entry.is_object()) return fail(where, "must be an object with min and max, found " + type_of(entry));
        for (const auto& [key, unused] : entry.items()) {
            (void)unused;
            if (key != "min" && key != "max") return fail(where + "/" + key, "unknown key (expected min, max)");
        }
        JointLimit limit;
        limit.limited = true;
        for (const char* which : {"min", "max"}) {
            const std::string wp = where + "/" + which;
            if (!entry.contains(which)) return fail(wp, "missing");
            const json& arr = entry[which];
            if (!arr.is_array() || arr.size() != 3) return fail(wp, "must be an array of 3 numbers [x, y, z]");
            for (size_t a = 0; a < 3; ++a) {
                const json& v = arr[a];
                const std::string ap = wp + "/" + std::to_string(a);
                if (!v.is_number()) return fail(ap, "must be a number, found " + type_of(v) + " " + v.dump());
                const double d = v.get<double>();
                if (!std::isfinite(d) || std::abs(d) > bound)
                    return fail(ap, "angle " + v.dump() + " is outside [-" + std::to_string(bound) + ", " + std::to_string(bound) + "]");
                glm::vec3& target = std::string(which) == "min" ? limit.min_angles : limit.max_angles;
                target[static_cast<int>(a)] = static_cast<float>(d) * to_radians;
            }
        }
        for (int a = 0; a < 3; ++a)
            if (limit.min_angles[a] > limit.max_angles[a])
                return fail(where, std::string("min exceeds max on axis ") + "XYZ"[a]);
        table.names.push_back(name);
        table.limits.push_back(limit);
    }
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
