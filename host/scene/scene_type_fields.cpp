// Reading a character type's humanoid map and motion files (scene_type_fields.hpp).
#include "host/scene/scene_type_fields.hpp"

#include "host/scene/scene_loader.hpp"

#include <algorithm>

namespace aloha {

void read_humanoid_map(JsonObjectReader& reader, std::map<std::string, std::string>& out) {
    const nlohmann::json* map = reader.child("humanoid_map");
    if (!map) return;
    if (!map->is_object() || map->size() > 1024) {
        reader.error("humanoid_map", "expected an object of canonical joint name -> joint name in the file");
        return;
    }
    for (const auto& [canonical, file_name] : map->items()) {
        if (!file_name.is_string() || file_name.get_ref<const std::string&>().empty())
            reader.error("humanoid_map/" + canonical, "expected the name of a joint in the file");
        else out[canonical] = file_name.get<std::string>();
    }
}

void read_walk_names(JsonObjectReader& reader, std::vector<std::string>& out) {
    const nlohmann::json* walks = reader.child("walks");
    if (!walks) return;
    if (!walks->is_array() || walks->empty() || walks->size() > 256) {
        reader.error("walks", "expected an array of 1 to 256 animation names");
        return;
    }
    for (size_t i = 0; i < walks->size(); ++i) {
        const nlohmann::json& name = (*walks)[i];
        if (!name.is_string() || name.get_ref<const std::string&>().empty())
            reader.error("walks/" + std::to_string(i), "expected the name of one of the file's animations");
        else if (std::find(out.begin(), out.end(), name.get<std::string>()) != out.end())
            reader.error("walks/" + std::to_string(i), "'" + name.get<std::string>() + "' is named twice");
        else out.push_back(name.get<std::string>());
    }
}

void read_motion_files(JsonObjectReader& reader, const std::string& pointer, const std::string& scene_file, CharacterTypeDesc& type,
                       std::vector<Error>& errors) {
    const nlohmann::json* motions = reader.child("motions");
    if (!motions) return;
    if (!motions->is_array() || motions->empty() || motions->size() > 256) {
        reader.error("motions", "expected an array of 1 to 256 motion files ({\"bvh\": ...} or {\"gltf\": ...})");
        return;
    }
    for (size_t i = 0; i < motions->size(); ++i) {
        MotionFileDesc m;
        m.pointer = pointer + "/motions/" + std::to_string(i);
        JsonObjectReader r((*motions)[i], m.pointer, scene_file, errors);
        auto resolve = [&](const char* key) -> std::string {
            const std::string ref = r.string(key, "");
            if (ref.empty()) return {};
            Result<std::string> path = resolve_scene_path(scene_file, ref, m.pointer + "/" + key);
            if (!path.ok()) {
                errors.push_back(path.error());
                return {};
            }
            return path.value();
        };
        m.bvh = resolve("bvh");
        m.gltf = resolve("gltf");
        m.clip = r.string("clip", "");
        m.name = r.string("name", "");
        m.scale = static_cast<float>(r.number("scale", 0.0, 1e-6, 1e6));
        m.walk = r.boolean("walk", false);
        read_humanoid_map(r, m.humanoid_map);
        const nlohmann::json& raw = (*motions)[i];
        auto given = [&](const char* key) { return raw.is_object() && raw.contains(key) && raw[key].is_string() && !raw[key].get<std::string>().empty(); };
        if (r.is_object() && int{given("bvh")} + int{given("gltf")} != 1) r.error("", "give exactly one of 'bvh' and 'gltf'");
        if (r.has("clip") && !given("gltf")) r.error("clip", "'clip' picks one animation of a 'gltf' file");
        if (r.has("name") && m.name.empty()) r.error("name", "expected a non-empty clip name");
        if (m.name.find('.') != std::string::npos) r.error("name", "a clip name after the type's prefix has no '.' ('" + m.name + "')");
        r.reject_unknown_keys();
        type.motions.push_back(std::move(m));
    }
}

}  // namespace aloha
