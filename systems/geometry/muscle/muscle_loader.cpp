#include "systems/geometry/muscle/muscle_loader.hpp"

#include "engine/core/json_reader.hpp"

#include <filesystem>

#include <nlohmann/json.hpp>

#include <cctype>
#include <cmath>
#include <fstream>
#include <sstream>

namespace aloha {

namespace {

using nlohmann::json;

// Reads JSON values at a path, recording the first problem with its JSON path.
struct Reader {
    const std::string& file;
    std::vector<Error> errors;

    void fail(const std::string& path, const std::string& what) { errors.push_back(make_error(file, what, 0, 0, path)); }

    bool number(const json& obj, const char* key, const std::string& path, float& out, bool required) {
        const auto it = obj.find(key);
        if (it == obj.end()) {
            if (required) fail(path + "/" + key, std::string("missing required field '") + key + "'");
            return false;
        }
        if (!it->is_number()) {
            fail(path + "/" + key, std::string("'") + key + "' must be a number");
            return false;
        }
        out = it->get<float>();
        if (!std::isfinite(out)) fail(path + "/" + key, std::string("'") + key + "' is not finite");
        return true;
    }

    template <int N>
    bool vec(const json& obj, const char* key, const std::string& path, glm::vec<N, float>& out, bool required) {
        const auto it = obj.find(key);
        if (it == obj.end()) {
            if (required) fail(path + "/" + key, std::string("missing required field '") + key + "'");
            return false;
        }
        if (!it->is_array() || it->size() != N) {
            fail(path + "/" + key, std::string("'") + key + "' must be an array of " + std::to_string(N) + " numbers");
            return false;
        }
        for (int k = 0; k < N; ++k) {
            const json& v = (*it)[static_cast<size_t>(k)];
            if (!v.is_number()) {
                fail(path + "/" + key + "/" + std::to_string(k), "must be a number");
                return false;
            }
            out[k] = v.get<float>();
        }
        return true;
    }

    bool string(const json& obj, const char* key, const std::string& path, std::string& out) {
        const auto it = obj.find(key);
        if (it == obj.end()) {
            fail(path + "/" + key, std::string("missing required field '") + key + "'");
            return false;
        }
        if (!it->is_string() || it->get_ref<const std::string&>().empty()) {
            fail(path + "/" + key, std::string("'") + key + "' must be a non-empty string");
            return false;
        }
        out = it->get<std::string>();
        return true;
    }

    void anchor(const json& obj, const char* key, const std::string& path, MuscleAnchor& a) {
        const auto it = obj.find(key);
        const std::string where = path + "/" + key;
        if (it == obj.end()) return fail(where, std::string("missing required field '") + key + "'");
        if (!it->is_object()) return fail(where, std::string("'") + key + "' must be an object {joint, along, offset}");
        string(*it, "joint", where, a.joint);
        number(*it, "along", where, a.along, false);
        vec<3>(*it, "offset", where, a.offset, false);
    }
};

}  // namespace

std::string mirror_joint_name(std::string_view name) {
    auto starts = [&](std::string_view p) { return name.substr(0, p.size()) == p; };
    if (starts("Left")) return "Right" + std::string(name.substr(4));
    if (starts("Right")) return "Left" + std::string(name.substr(5));
    if (name.size() >= 2 && (name[0] == 'L' || name[0] == 'R') && std::isupper(static_cast<unsigned char>(name[1])))
        return std::string(1, name[0] == 'L' ? 'R' : 'L') + std::string(name.substr(1));
    if (name == "lhand") return "rhand";
    if (name == "rhand") return "lhand";
    return std::string(name);
}

MuscleDef mirror_muscle(const MuscleDef& def, const std::string& mirror_name) {
    MuscleDef m = def;
    m.name = mirror_name;
    m.origin.joint = mirror_joint_name(def.origin.joint);
    m.insertion.joint = mirror_joint_name(def.insertion.joint);
    m.origin.offset.x = -m.origin.offset.x;
    m.insertion.offset.x = -m.insertion.offset.x;
    m.depth_axis.x = -m.depth_axis.x;
    return m;
}

Result<std::vector<MuscleDef>> parse_muscle_defs(const json& doc, const std::string& source_name) {
    Reader r{source_name, {}};
    std::vector<MuscleDef> defs;
    if (!doc.is_object()) return make_error(source_name, "top level must be an object with a 'muscles' array", 0, 0, "/");
    if (doc.contains("version") && !(doc["version"].is_number_integer() && doc["version"].get<int>() == 1))
        return make_error(source_name, "unsupported version (expected 1)", 0, 0, "/version");
    MuscleDef defaults;
    if (const auto it = doc.find("defaults"); it != doc.end()) {
        if (!it->is_object()) return make_error(source_name, "'defaults' must be an object", 0, 0, "/defaults");
        glm::vec2 ab(defaults.exponent_a, defaults.exponent_b);
        if (r.vec<2>(*it, "exponents", "/defaults", ab, false)) {
            defaults.exponent_a = ab.x;
            defaults.exponent_b = ab.y;
        }
        r.number(*it, "fat_thickness", "/defaults", defaults.fat_thickness, false);
    }
    const auto list = doc.find("muscles");
    if (list == doc.end()) return make_error(source_name, "missing required field 'muscles'", 0, 0, "/muscles");
    if (!list->is_array()) return make_error(source_name, "'muscles' must be an array", 0, 0, "/muscles");
    for (size_t i = 0; i < list->size(); ++i) {
        const json& m = (*list)[i];
        const std::string path = "/muscles/" + std::to_string(i);
        if (!m.is_object()) {
            r.fail(path, "each muscle must be an object");
            continue;
        }
        MuscleDef d = defaults;
        d.source_path = path;
        r.string(m, "name", path, d.name);
        r.anchor(m, "origin", path, d.origin);
        r.anchor(m, "insertion", path, d.insertion);
        const bool has_radii = r.vec<2>(m, "radii", path, d.rest_radii, false);
        const bool has_volume = r.number(m, "volume", path, d.volume, false);
        if (has_radii == has_volume)
            r.fail(path, "give exactly one of 'radii' [width, depth] (m) or 'volume' (m^3) with 'ratio'");
        if (has_radii && (!(d.rest_radii.x > 0.0f) || !(d.rest_radii.y > 0.0f)))
            r.fail(path + "/radii", "radii must be positive metres");
        if (has_volume) r.number(m, "ratio", path, d.ratio, true);
        glm::vec2 ab(d.exponent_a, d.exponent_b);
        if (r.vec<2>(m, "exponents", path, ab, false)) {
            d.exponent_a = ab.x;
            d.exponent_b = ab.y;
        }
        r.number(m, "fat_thickness", path, d.fat_thickness, false);
        r.vec<3>(m, "depth_axis", path, d.depth_axis, false);
        defs.push_back(d);
        if (const auto mir = m.find("mirror"); mir != m.end()) {
            if (!mir->is_string() || mir->get_ref<const std::string&>().empty()) r.fail(path + "/mirror", "'mirror' must be the name of the mirrored copy");
            else defs.push_back(mirror_muscle(d, mir->get<std::string>()));
        }
    }
    if (!r.errors.empty()) {
        Error first = r.errors.front();
        if (r.errors.size() > 1)
            first.message += "\n" + join_errors(std::vector<Error>(r.errors.begin() + 1, r.errors.end()));
        return first;
    }
    return defs;
}

Result<std::vector<MuscleDef>> load_muscle_defs(const std::string& path) {
    std::error_code ec;
    if (std::filesystem::is_directory(path, ec)) return make_error(path, "is a folder, not a regular file");
    std::ifstream in(path, std::ios::binary);
    if (!in) return make_error(path, "cannot open muscle layout file");
    std::stringstream buffer;
    buffer << in.rdbuf();
    const std::string text = buffer.str();
    auto doc = parse_json_text(text, path);
    if (!doc.ok()) return doc.error();
    return parse_muscle_defs(doc.value(), path);
}

void scale_muscle_defs(std::vector<MuscleDef>& defs, float length, float girth, float fat) {
    for (MuscleDef& d : defs) {
        d.origin.offset *= length;
        d.insertion.offset *= length;
        d.rest_radii *= length * girth;
        d.volume *= length * length * length * girth * girth;
        d.fat_thickness *= fat;
    }
}

Result<MuscleSet> load_muscle_set(const std::string& path, const Skeleton& skeleton) {
    auto defs = load_muscle_defs(path);
    if (!defs.ok()) return defs.error();
    return resolve_muscles(defs.value(), skeleton, path);
}

}  // namespace aloha
