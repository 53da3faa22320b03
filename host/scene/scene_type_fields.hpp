// Fields of a scene's character type that are objects of their own: the explicit humanoid map and the motion
// files (docs/SCENES.md). Read by scene_loader.cpp; errors go to the scene's error list with their JSON pointer.
#pragma once

#include "engine/core/json_reader.hpp"
#include "host/scene/scene_desc.hpp"

#include <map>
#include <string>
#include <vector>

namespace aloha {

/// Reads `reader`'s "humanoid_map" (canonical joint name -> the file's joint name) into `out`, when present.
void read_humanoid_map(JsonObjectReader& reader, std::map<std::string, std::string>& out);

/// Reads a bvh/gltf type's optional "walks": 1 to 256 names of its file's animations to use as its walks (errors at
/// "walks" or "walks/i" for another shape, an empty name or a name given twice).
void read_walk_names(JsonObjectReader& reader, std::vector<std::string>& out);

/// Reads `reader`'s "motions" (the type at `pointer` in `scene_file`) into `type.motions`, when present: an array of
/// up to 256 objects, each with exactly one of "bvh" and "gltf" (paths relative to the scene, as a type's), and
/// optionally "clip" (glTF only), "name", "humanoid_map", "scale" and "walk".
void read_motion_files(JsonObjectReader& reader, const std::string& pointer, const std::string& scene_file, CharacterTypeDesc& type,
                       std::vector<Error>& errors);

}  // namespace aloha
