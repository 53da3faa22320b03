#include "host/scene/scene_loader.hpp"

#include "engine/core/json_reader.hpp"
#include "host/scene/scene_requests.hpp"
#include "host/scene/scene_type_fields.hpp"

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

// The installed data folder (share/aloha under the install prefix), set by host/scene/CMakeLists.txt.
// Never a source-tree path: a build-tree program names its folder with set_data_directory().
#ifndef ALOHA_INSTALL_DATA_DIR
#error "ALOHA_INSTALL_DATA_DIR must be defined by the build"
#endif

namespace aloha {

namespace fs = std::filesystem;

namespace {
std::string& chosen_data_directory() {
    static std::string folder;
    return folder;
}
}  // namespace

void set_data_directory(const std::string& folder) { chosen_data_directory() = folder; }

std::string data_directory() {
    if (const char* env = std::getenv("ALOHA_DATA_DIR"); env && *env) return env;
    if (!chosen_data_directory().empty()) return chosen_data_directory();
    return ALOHA_INSTALL_DATA_DIR;
}

namespace {

// Built-in names and the files they stand for, relative to the data folder.
const std::map<std::string, std::string>& builtin_files() {
    static const std::map<std::string, std::string> files = {
        {"humanoid", "characters/humanoid.json"},
        {"humanoid_muscles", "characters/humanoid_muscles.json"},
        {"humanoid_limits", "characters/humanoid_limits.json"},
        {"default", "rules/default.json"},
    };
    return files;
}

bool is_inside(const fs::path& folder, const fs::path& candidate) {
    auto f = folder.lexically_normal();
    auto c = candidate.lexically_normal();
    auto fi = f.begin(), ci = c.begin();
    for (; fi != f.end() && !fi->empty(); ++fi, ++ci)
        if (ci == c.end() || *fi != *ci) return false;
    return true;
}

Result<std::string> read_file(const std::string& path) {
    std::error_code ec;
    if (!fs::exists(path, ec)) return make_error(path, "file does not exist");
    if (fs::is_directory(path, ec)) return make_error(path, "is a folder, not a file");
    const auto size = fs::file_size(path, ec);
    if (ec) return make_error(path, "cannot read file size: " + ec.message());
    if (size > (64u << 20)) return make_error(path, "file is larger than 64 MiB; refusing to read it");
    std::ifstream in(path, std::ios::binary);
    if (!in) return make_error(path, "cannot open file for reading");
    std::ostringstream ss;
    ss << in.rdbuf();
    return ss.str();
}

void read_camera(JsonObjectReader& root, SceneDesc& scene, std::vector<Error>& errors) {
    const nlohmann::json* cam = root.child("camera");
    if (!cam) {
        root.error("camera", "required object is missing");
        return;
    }
    JsonObjectReader c(*cam, "/camera", scene.file, errors);
    scene.camera.fov_y_deg = static_cast<float>(c.number("fov_deg", 50.0, 1.0, 170.0));
    scene.camera.near_plane = static_cast<float>(c.number("near", 0.1, 1e-4, 1e4));
    scene.camera.far_plane = static_cast<float>(c.number("far", 1000.0, 1e-3, 1e7));
    if (scene.camera.far_plane <= scene.camera.near_plane) c.error("far", "far plane must be beyond the near plane");
    if (const nlohmann::json* keys = c.child("keys")) {
        if (!keys->is_array() || keys->empty()) {
            c.error("keys", "expected a non-empty array of {time, position, target}");
        } else if (keys->size() > 100000) {
            c.error("keys", "more than 100000 camera keys");
        } else {
            for (size_t i = 0; i < keys->size(); ++i) {
                const std::string p = "/camera/keys/" + std::to_string(i);
                JsonObjectReader k((*keys)[i], p, scene.file, errors);
                CameraKey key;
                key.time = static_cast<float>(k.number("time", 0.0, 0.0, 1e6, true));
                key.position = k.vec3("position", key.position, true);
                key.target = k.vec3("target", key.target, true);
                k.reject_unknown_keys();
                if (!scene.camera.keys.empty() && key.time <= scene.camera.keys.back().time)
                    errors.push_back(make_error(scene.file, "key times must increase", 0, 0, p + "/time"));
                scene.camera.keys.push_back(key);
            }
        }
        if (c.has("position") || c.has("target")) c.error("", "give either keys or position/target, not both");
    } else {
        CameraKey key;
        key.position = c.vec3("position", key.position, true);
        key.target = c.vec3("target", key.target, true);
        scene.camera.keys.push_back(key);
    }
    for (const CameraKey& k : scene.camera.keys)
        if (glm::length(k.target - k.position) < 1e-4f) {
            c.error("", "camera position and target coincide");
            break;
        }
    c.reject_unknown_keys();
}

void read_types(JsonObjectReader& root, SceneDesc& scene, std::vector<Error>& errors) {
    const nlohmann::json* types = root.child("character_types");
    if (!types) {  // default: the built-in humanoid
        CharacterTypeDesc t;
        t.name = "humanoid";
        auto def = resolve_scene_path(scene.file, "builtin:humanoid", "/character_types");
        if (!def.ok()) errors.push_back(def.error());
        else t.humanoid = def.value();
        scene.types.push_back(t);
        return;
    }
    if (!types->is_array() || types->empty() || types->size() > 256) {
        root.error("character_types", "expected an array of 1 to 256 character types");
        return;
    }
    for (size_t i = 0; i < types->size(); ++i) {
        const std::string p = "/character_types/" + std::to_string(i);
        JsonObjectReader r((*types)[i], p, scene.file, errors);
        CharacterTypeDesc t;
        t.name = r.string("name", "", true);
        auto resolve = [&](const char* key) -> std::string {
            std::string ref = r.string(key, "");
            if (ref.empty()) return {};
            auto res = resolve_scene_path(scene.file, ref, p + "/" + key);
            if (!res.ok()) {
                errors.push_back(res.error());
                return {};
            }
            return res.value();
        };
        t.humanoid = resolve("humanoid");
        t.bvh = resolve("bvh");
        t.gltf = resolve("gltf");
        t.muscles = resolve("muscles");
        t.limits = resolve("limits");
        t.scene_file = scene.file;
        t.pointer = p;
        t.scale = static_cast<float>(r.number("scale", 0.0, 1e-6, 1e6));
        read_humanoid_map(r, t.humanoid_map);
        read_walk_names(r, t.walks);
        read_motion_files(r, p, scene.file, t, errors);
        if (!t.bvh.empty() || !t.gltf.empty()) {
            auto canonical = resolve_scene_path(scene.file, "builtin:humanoid", p);
            if (canonical.ok()) t.canonical = canonical.value();
            else errors.push_back(canonical.error());
        }
        t.generated_motion = r.boolean("generated_motion", true);
        t.idle = r.string("idle", "");
        t.height = static_cast<float>(r.number("height", 1.75, 0.5, 2.5));
        t.build = static_cast<float>(r.number("build", 0.5, 0.0, 1.0));
        // Counted from the file, not from the resolved paths: a path refused above is one error, not two.
        const nlohmann::json& raw = (*types)[i];
        auto given = [&](const char* key) { return raw.is_object() && raw.contains(key) && raw[key].is_string() && !raw[key].get<std::string>().empty(); };
        const int sources = int{given("humanoid")} + int{given("bvh")} + int{given("gltf")};
        if (sources != 1 && r.is_object()) r.error("", "give exactly one of 'humanoid', 'bvh' or 'gltf'");
        if (t.humanoid.empty() && (r.has("height") || r.has("build")))
            r.error("height", "'height' and 'build' apply to 'humanoid' types only");
        if (!t.humanoid.empty() && (r.has("scale") || r.has("humanoid_map")))
            r.error(r.has("scale") ? "scale" : "humanoid_map", "'scale' and 'humanoid_map' apply to 'bvh' and 'gltf' types only");
        if (!t.humanoid.empty() && r.has("walks"))
            r.error("walks", "'walks' applies to 'bvh' and 'gltf' types only (a 'humanoid' type walks its generated gaits)");
        if (!t.humanoid.empty() && r.has("generated_motion"))
            r.error("generated_motion", "'generated_motion' applies to 'bvh' and 'gltf' types only (a 'humanoid' type's motion is generated)");
        if (t.bvh.size() > 5 && t.bvh.compare(t.bvh.size() - 5, 5, ".json") == 0)
            r.error("bvh", "this is a JSON file, not a BVH skeleton; the project's humanoid is \"humanoid\": \"builtin:humanoid\"");
        r.reject_unknown_keys();
        for (const auto& other : scene.types)
            if (other.name == t.name) r.error("name", "duplicate character type '" + t.name + "'");
        scene.types.push_back(t);
    }
}

int find_type(const SceneDesc& scene, const std::string& name) {
    for (size_t i = 0; i < scene.types.size(); ++i)
        if (scene.types[i].name == name) return static_cast<int>(i);
    return -1;
}

void read_paths(JsonObjectReader& root, SceneDesc& scene, std::vector<Error>& errors) {
    const nlohmann::json* paths = root.child("paths");
    if (!paths) return;
    if (!paths->is_array() || paths->size() > 10000) {
        root.error("paths", "expected an array of at most 10000 paths");
        return;
    }
    for (size_t i = 0; i < paths->size(); ++i) {
        const std::string p = "/paths/" + std::to_string(i);
        JsonObjectReader r((*paths)[i], p, scene.file, errors);
        PathDesc path;
        path.name = r.string("name", "", true);
        path.loop = r.boolean("loop", true);
        const nlohmann::json* pts = r.child("points");
        if (!pts || !pts->is_array() || pts->size() < 2 || pts->size() > 100000) {
            r.error("points", "expected an array of 2 to 100000 points");
        } else {
            for (size_t k = 0; k < pts->size(); ++k)
                path.points.push_back(read_vec3((*pts)[k], p + "/points/" + std::to_string(k), scene.file, errors, {}));
        }
        r.reject_unknown_keys();
        scene.paths.push_back(path);
    }
}

// Gives every crowd with a height or build range its own body variants: types that copy the
// crowd's type with heights spread evenly over the range and builds spread by the golden
// ratio (so height and build are not correlated). Their clips keep the base type's names. A file's
// character (bvh, gltf) varies in height only, scaled uniformly to each (standing_height).
void add_body_variants(SceneDesc& scene, std::vector<Error>& errors) {
    for (size_t ci = 0; ci < scene.crowds.size(); ++ci) {
        CrowdDesc& crowd = scene.crowds[ci];
        if (crowd.variants == 0 || scene.types.empty()) continue;
        const CharacterTypeDesc base = scene.types[static_cast<size_t>(crowd.type)];
        if (base.humanoid.empty() && crowd.build_max >= 0.0f) {
            errors.push_back(make_error(scene.file, "build variety needs a 'humanoid' character type ('" + base.name +
                                                        "' is a file's character: give it a 'height' range, which scales it)",
                                        0, 0, "/crowds/" + std::to_string(ci) + "/build"));
            continue;
        }
        for (uint32_t v = 0; v < crowd.variants; ++v) {
            CharacterTypeDesc t = base;
            const float u = (static_cast<float>(v) + 0.5f) / static_cast<float>(crowd.variants);
            const float g = std::fmod(0.5f + 0.6180340f * static_cast<float>(v), 1.0f);
            if (crowd.height_max > 0.0f) {
                const float height = crowd.height_min + (crowd.height_max - crowd.height_min) * u;
                (base.humanoid.empty() ? t.standing_height : t.height) = height;  // a file's character is scaled to it
            }
            if (crowd.build_max >= 0.0f) t.build = crowd.build_min + (crowd.build_max - crowd.build_min) * g;
            t.name = base.name + "~" + std::to_string(ci) + "." + std::to_string(v);
            t.variant_of = "/crowds/" + std::to_string(ci) + (crowd.height_max > 0.0f ? "/height" : "/build");
            t.clip_prefix = base.clip_prefix.empty() ? base.name : base.clip_prefix;
            crowd.variant_types.push_back(static_cast<int>(scene.types.size()));
            scene.types.push_back(std::move(t));
        }
    }
}

}  // namespace

Result<std::string> resolve_scene_path(const std::string& scene_file, const std::string& reference,
                                       const std::string& json_path) {
    const std::string prefix = "builtin:";
    if (reference.rfind(prefix, 0) == 0) {
        const std::string name = reference.substr(prefix.size());
        auto it = builtin_files().find(name);
        if (it == builtin_files().end())
            return make_error(scene_file, "unknown built-in '" + name + "'", 0, 0, json_path);
        const std::string full = data_directory() + "/" + it->second;
        if (!fs::exists(full))
            return make_error(scene_file, "built-in '" + name + "' is missing at " + full + " (set ALOHA_DATA_DIR?)", 0, 0, json_path);
        return full;
    }
    const fs::path ref(reference);
    if (ref.is_absolute())
        return make_error(scene_file, "absolute path '" + reference + "' is not allowed; use a path relative to the scene's folder", 0, 0, json_path);
    const fs::path folder = fs::absolute(fs::path(scene_file)).parent_path();
    const fs::path full = (folder / ref).lexically_normal();
    if (!is_inside(folder, full))
        return make_error(scene_file, "path '" + reference + "' escapes the scene's folder", 0, 0, json_path);
    if (!fs::exists(full)) return make_error(scene_file, "referenced file '" + reference + "' does not exist", 0, 0, json_path);
    // Symbolic links are followed before comparing, so a link inside the folder cannot lead out of it.
    std::error_code ec;
    const fs::path real_folder = fs::weakly_canonical(folder, ec), real_full = fs::weakly_canonical(full, ec);
    if (ec || !is_inside(real_folder, real_full))
        return make_error(scene_file, "path '" + reference + "' escapes the scene's folder through a symbolic link", 0, 0, json_path);
    return full.string();
}

Result<SceneDesc> parse_scene(const std::string& text, const std::string& file) {
    auto parsed = parse_json_text(text, file);
    if (!parsed.ok()) return parsed.error();
    const nlohmann::json& j = parsed.value();
    std::vector<Error> errors;
    SceneDesc scene;
    scene.file = fs::absolute(fs::path(file)).lexically_normal().string();
    JsonObjectReader root(j, "", scene.file, errors);
    if (!root.is_object()) return errors.front();
    (void)root.string("$schema", "");      // editor hint (data/schemas/scene.schema.json)
    (void)root.string("description", "");  // free text for people
    scene.name = root.string("name", fs::path(file).stem().string());
    scene.frames = static_cast<uint32_t>(root.integer("frames", 300, 1, 10'000'000));
    scene.dt = static_cast<float>(root.number("dt", 1.0 / 60.0, 1e-5, 1.0));
    scene.seed = static_cast<uint64_t>(root.integer("seed", 1, 0, INT64_MAX));
    if (const nlohmann::json* vp = root.child("viewport")) {
        JsonObjectReader v(*vp, "/viewport", scene.file, errors);
        scene.width = static_cast<uint32_t>(v.integer("width", 1280, 16, 8192));
        scene.height = static_cast<uint32_t>(v.integer("height", 720, 16, 8192));
        v.reject_unknown_keys();
    }
    {
        const std::string rules = root.string("rules", "builtin:default");
        auto res = resolve_scene_path(scene.file, rules, "/rules");
        if (res.ok()) scene.rules = res.value();
        else errors.push_back(res.error());
    }
    scene.tier = root.string("tier", "");  // checked against the rule file's tiers when the world loads
    read_camera(root, scene, errors);
    read_types(root, scene, errors);
    read_paths(root, scene, errors);
    read_characters(root, scene, errors);
    read_crowds(root, scene, errors);
    add_body_variants(scene, errors);
    root.reject_unknown_keys();
    if (errors.empty() && character_count(scene) == 0)
        errors.push_back(make_error(scene.file, "scene has no characters (add 'characters' or 'crowds')", 0, 0, "/"));
    if (!errors.empty()) return first_and_rest(errors);
    return scene;
}

Result<SceneDesc> load_scene(const std::string& path) {
    auto text = read_file(path);
    if (!text.ok()) return text.error();
    return parse_scene(text.value(), path);
}

int scene_type_index(const SceneDesc& scene, const std::string& name) { return find_type(scene, name); }

}  // namespace aloha
