// Loads scene files (JSON; format in docs/SCENES.md, schema in data/schemas/scene.schema.json).
#pragma once

#include "engine/core/result.hpp"
#include "host/scene/scene_desc.hpp"

#include <string>

namespace aloha {

/// Upper bound on the characters one scene may spawn (protects against 1e9-character files).
inline constexpr uint64_t kMaxSceneCharacters = 1'000'000;

/// Folder holding ALOHA's data (rules, characters, scenes): $ALOHA_DATA_DIR when set, else the folder
/// given to set_data_directory(), else the installed share/aloha.
std::string data_directory();

/// Names the data folder for this process (a program run from a build tree names the source tree's
/// data/). Call once at start-up, before loading scenes; $ALOHA_DATA_DIR still takes precedence.
void set_data_directory(const std::string& folder);

/// Resolves `reference` written in `scene_file`: "builtin:NAME" names a file under the data folder
/// (see docs/SCENES.md); any other value is a path relative to the scene's folder that must stay inside
/// it (absolute paths and ".." escapes are errors). `json_path` places errors.
Result<std::string> resolve_scene_path(const std::string& scene_file, const std::string& reference,
                                       const std::string& json_path);

/// Reads and validates a scene file. Every problem found is reported (joined in one Error message,
/// each line naming the file and JSON path); missing referenced files are errors.
Result<SceneDesc> load_scene(const std::string& path);

/// Same as load_scene for JSON text already in memory; `file` names it in errors and anchors paths.
Result<SceneDesc> parse_scene(const std::string& text, const std::string& file);

}  // namespace aloha
