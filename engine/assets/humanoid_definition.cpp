#include "engine/assets/humanoid_definition.hpp"

#include "engine/assets/file_io.hpp"
#include "engine/core/json_reader.hpp"

#include <cmath>
#include <filesystem>
#include <map>

namespace aloha {

namespace {

namespace fs = std::filesystem;

// Width factor of lateral offsets (hip and shoulder joint spacing) for a build in [0, 1]:
// slim 0.94, average 1.0, heavy 1.06 of the table's widths.
float lateral_factor(float build) { return 0.94f + 0.12f * build; }

// Resolves a file named in the definition relative to the definition's folder; it must exist.
std::string sibling(const std::string& def_file, const std::string& name, const std::string& json_path,
                    std::vector<Error>& errors) {
    if (name.empty()) return {};
    const fs::path p = fs::path(def_file).parent_path() / name;
    std::error_code ec;
    if (!fs::is_regular_file(p, ec)) {
        errors.push_back(make_error(def_file, "file '" + name + "' named here does not exist next to the definition", 0, 0,
                                    json_path));
        return {};
    }
    return p.lexically_normal().string();
}

void read_joints(JsonObjectReader& root, HumanoidDefinition& def, std::vector<Error>& errors) {
    const nlohmann::json* joints = root.child("joints");
    if (!joints || !joints->is_array() || joints->empty() || joints->size() > 1024) {
        root.error("joints", "expected an array of 1 to 1024 joints");
        return;
    }
    std::map<std::string, int> index;         // joint name -> raw index
    std::map<std::string, std::string> mirror;  // left name -> right name
    auto add = [&](const std::string& name, const std::string& parent, glm::vec3 offset, const std::string& where) {
        if (index.count(name)) {
            errors.push_back(make_error(def.file, "duplicate joint name '" + name + "'", 0, 0, where));
            return;
        }
        RawJoint j;
        j.name = name;
        j.translation = offset;
        if (!parent.empty()) {
            auto it = index.find(parent);
            if (it == index.end()) {
                errors.push_back(make_error(def.file, "parent '" + parent + "' is not defined before this joint", 0, 0,
                                            where + "/parent"));
                return;
            }
            j.parent = it->second;
        } else if (!def.unit_skeleton.joints.empty()) {
            errors.push_back(make_error(def.file, "only the first joint may have no parent", 0, 0, where));
            return;
        }
        index[name] = static_cast<int>(def.unit_skeleton.joints.size());
        def.unit_skeleton.joints.push_back(j);
    };
    for (size_t i = 0; i < joints->size(); ++i) {
        const std::string p = "/joints/" + std::to_string(i);
        JsonObjectReader r((*joints)[i], p, def.file, errors);
        const std::string name = r.string("name", "", true);
        const std::string parent = r.string("parent", "");
        const glm::vec3 offset = r.vec3("offset", glm::vec3(0.0f), true);
        const bool lateral = r.boolean("lateral", false);
        const std::string mirror_name = r.string("mirror", "");
        (void)r.string("note", "");
        r.reject_unknown_keys();
        if (glm::length(offset) > 2.0f) r.error("offset", "offset is longer than twice the standing height");
        if (name.empty()) continue;
        add(name, parent, offset, p);
        def.lateral.push_back(lateral);
        if (!mirror_name.empty()) {
            mirror[name] = mirror_name;
            const std::string mirrored_parent = mirror.count(parent) ? mirror[parent] : parent;
            add(mirror_name, mirrored_parent, glm::vec3(-offset.x, offset.y, offset.z), p + "/mirror");
            def.lateral.push_back(lateral);
        }
    }
}

}  // namespace

Result<HumanoidDefinition> load_humanoid_definition(const std::string& path) {
    Result<std::string> text = read_text_file(path);
    if (!text.ok()) return text.error();
    auto parsed = parse_json_text(text.value(), path);
    if (!parsed.ok()) return parsed.error();
    std::vector<Error> errors;
    HumanoidDefinition def;
    def.file = fs::absolute(fs::path(path)).lexically_normal().string();
    JsonObjectReader root(parsed.value(), "", def.file, errors);
    if (!root.is_object()) return errors.front();
    (void)root.string("$schema", "");
    (void)root.string("description", "");
    (void)root.string("units", "");
    (void)root.string("mirror", "");
    if (const std::string format = root.string("format", "", true); !format.empty() && format != "aloha-humanoid")
        root.error("format", "expected \"aloha-humanoid\", found \"" + format + "\"");
    if (root.integer("version", 1, 1, 1, true) != 1) root.error("version", "only version 1 is supported");
    def.reference_height = static_cast<float>(root.number("reference_height", 1.75, 0.5, 2.5, true));
    def.muscles = sibling(def.file, root.string("muscles", ""), "/muscles", errors);
    def.limits = sibling(def.file, root.string("limits", ""), "/limits", errors);
    read_joints(root, def, errors);
    root.reject_unknown_keys();
    if (!errors.empty()) {
        Error e = errors.front();
        if (errors.size() > 1)
            e.message += " (and " + std::to_string(errors.size() - 1) + " more:\n" +
                         join_errors(std::vector<Error>(errors.begin() + 1, errors.end())) + ")";
        return e;
    }
    return def;
}

Status validate_humanoid_body(const HumanoidBody& body, const std::string& source, const std::string& where) {
    if (!(std::isfinite(body.height) && body.height >= 0.5f && body.height <= 2.5f))
        return make_error(source, "height " + std::to_string(body.height) + " m is outside [0.5, 2.5] m", 0, 0, where);
    if (!(std::isfinite(body.build) && body.build >= 0.0f && body.build <= 1.0f))
        return make_error(source, "build " + std::to_string(body.build) + " is outside [0, 1] (0 slim, 1 heavy)", 0, 0, where);
    return {};
}

RawSkeleton humanoid_skeleton(const HumanoidDefinition& def, const HumanoidBody& body) {
    RawSkeleton out = def.unit_skeleton;
    const float wide = lateral_factor(body.build);
    for (size_t i = 0; i < out.joints.size(); ++i) {
        glm::vec3 t = out.joints[i].translation * body.height;
        if (i < def.lateral.size() && def.lateral[i]) t.x *= wide;
        out.joints[i].translation = t;
    }
    return out;
}

}  // namespace aloha
