// Scene-file sections for placed characters, their request queues and crowd generators
// (the part of the scene loader that deals with who is in the scene and what they do).
#pragma once

#include "engine/core/json_reader.hpp"
#include "host/scene/scene_desc.hpp"

#include <string>
#include <vector>

namespace aloha {

/// Index of the character type called `name` in `scene`, or -1.
int scene_type_index(const SceneDesc& scene, const std::string& name);

/// Reads one request object at `path` ({"type": "play"|"walk"|"reach"|"look_at"|"rest", ...}). With `weight`,
/// the object may also hold a "weight" in [0, 1] (an overlay's), written there (default 1).
RequestDesc read_request(const nlohmann::json& value, const std::string& path, const SceneDesc& scene,
                         std::vector<Error>& errors, float* weight = nullptr);

/// Reads the optional "characters" array into scene.characters.
void read_characters(JsonObjectReader& root, SceneDesc& scene, std::vector<Error>& errors);

/// Reads the optional "crowds" array into scene.crowds (counts capped by kMaxSceneCharacters).
void read_crowds(JsonObjectReader& root, SceneDesc& scene, std::vector<Error>& errors);

}  // namespace aloha
