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

// One anchor {joint, along, offset} of a muscle.
void read_anchor(JsonObjectReader& muscle, const char* key, const std::string& file, std::vector<Error>& errors, MuscleAnchor& a) {
    const json* v = muscle.child(key);
    if (!v) return muscle.error("", std::string("missing required key '") + key + "'");
    JsonObjectReader r(*v, muscle.child_path(key), file, errors);
    a.joint = r.string("joint", "", true);
    r.read("along", a.along, -10.0, 10.0);
    a.offset = r.vec3("offset", a.offset, false, 10.0);
    r.reject_unknown_keys();
}

// Super-ellipsoid exponents [a, b] (both given together).
void read_exponents(JsonObjectReader& r, MuscleDef& d) {
    const glm::vec2 ab = r.vec2("exponents", glm::vec2(d.exponent_a, d.exponent_b), false, 100.0);
    d.exponent_a = ab.x;
    d.exponent_b = ab.y;
}

// "fat_regions": { NAME: { "normal_hz", "normal_damping", "lateral_hz", "max_strain" } } (each optional).
std::vector<FatRegion> read_fat_regions(JsonObjectReader& top, const std::string& file, std::vector<Error>& errors) {
    std::vector<FatRegion> regions;
    const json* v = top.child("fat_regions");
    if (!v) return regions;
    if (!v->is_object()) return top.error("fat_regions", std::string("expected an object of regions, got ") + v->type_name()), regions;
    if (v->size() > kMaxFatRegions)
        return top.error("fat_regions", "more than " + std::to_string(kMaxFatRegions) + " regions"), regions;
    for (const auto& [name, body] : v->items()) {
        JsonObjectReader r(body, top.child_path("fat_regions") + "/" + name, file, errors);
        FatRegion region;
        region.name = name;
        auto read = [&r](const char* key, std::optional<float>& out, double lo, double hi) {
            if (r.has(key)) out = static_cast<float>(r.number(key, lo, lo, hi));
        };
        read("normal_hz", region.normal_hz, 0.1, 1000.0);
        read("normal_damping", region.normal_damping, 0.0, 10.0);
        read("lateral_hz", region.lateral_hz, 0.1, 1000.0);
        read("max_strain", region.max_strain, 0.01, 1.0);
        r.allow({"description"});
        r.reject_unknown_keys();
        regions.push_back(std::move(region));
    }
    return regions;
}

// "fat_region": NAME of one of `regions` (an error listing them otherwise).
void read_fat_region(JsonObjectReader& r, std::span<const FatRegion> regions, MuscleDef& d) {
    if (!r.has("fat_region")) return;
    const std::string name = r.string("fat_region", "", true);
    std::string known;
    for (const FatRegion& region : regions) {
        if (region.name == name) return void(d.fat_region = region);
        known += (known.empty() ? "" : ", ") + region.name;
    }
    if (!name.empty())
        r.error("fat_region", "unknown fat region '" + name + "' (the file's \"fat_regions\" are: " + (known.empty() ? "none" : known) + ")");
}

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
    std::vector<Error> errors;
    std::vector<MuscleDef> defs;
    JsonObjectReader top(doc, "", source_name, errors);
    top.allow({"$schema", "description", "format", "skeleton", "units", "notes"});
    top.integer("version", 1, 1, 1);  // the only version so far
    MuscleDef defaults;
    const std::vector<FatRegion> regions = read_fat_regions(top, source_name, errors);
    if (const json* dj = top.child("defaults")) {
        JsonObjectReader d(*dj, "/defaults", source_name, errors);
        read_exponents(d, defaults);
        d.read("fat_thickness", defaults.fat_thickness, 0.0, 1.0);
        read_fat_region(d, regions, defaults);
        d.reject_unknown_keys();
    }
    const json* list = top.child("muscles");
    top.reject_unknown_keys();
    if (top.is_object() && !list) top.error("", "missing required key 'muscles'");
    else if (list && !list->is_array()) top.error("muscles", std::string("expected an array of muscles, got ") + list->type_name());
    for (size_t i = 0; list && list->is_array() && i < list->size(); ++i) {
        const std::string path = "/muscles/" + std::to_string(i);
        JsonObjectReader r((*list)[i], path, source_name, errors);
        if (!r.is_object()) continue;
        MuscleDef d = defaults;
        d.source_path = path;
        d.name = r.string("name", "", true);
        r.allow({"description"});
        read_anchor(r, "origin", source_name, errors, d.origin);
        read_anchor(r, "insertion", source_name, errors, d.insertion);
        const bool has_radii = r.has("radii"), has_volume = r.has("volume");
        if (has_radii == has_volume) r.error("", "give exactly one of 'radii' [width, depth] (m) or 'volume' (m^3) with 'ratio'");
        d.rest_radii = r.vec2("radii", d.rest_radii, false, 10.0);
        if (has_radii && (!(d.rest_radii.x > 0.0f) || !(d.rest_radii.y > 0.0f))) r.error("radii", "radii must be positive metres");
        r.read("volume", d.volume, 1e-9, 10.0);
        if (has_volume) d.ratio = static_cast<float>(r.number("ratio", d.ratio, 1e-3, 1e3, /*required=*/true));
        read_exponents(r, d);
        r.read("fat_thickness", d.fat_thickness, 0.0, 1.0);
        read_fat_region(r, regions, d);
        d.trunk_skin = r.boolean("trunk_skin", d.trunk_skin);
        d.depth_axis = r.vec3("depth_axis", d.depth_axis, false, 1e3);
        // The mirrored copy's name: a non-empty string when given (one error otherwise).
        const std::string mirror = r.has("mirror") ? r.string("mirror", "", /*required=*/true) : std::string();
        r.reject_unknown_keys();
        defs.push_back(d);
        if (!mirror.empty()) defs.push_back(mirror_muscle(d, mirror));
    }
    if (!errors.empty()) return first_and_rest(errors);
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
