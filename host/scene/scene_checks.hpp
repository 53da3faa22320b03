// Checks of a scene's requests against its loaded character types: what World would refuse when it
// queues them, found up front (aloha validate) with one error per distinct problem.
#pragma once

#include "engine/core/result.hpp"
#include "host/scene/character_type.hpp"
#include "host/scene/scene_desc.hpp"

#include <string>
#include <vector>

namespace aloha {

/// Why request `rd` cannot be queued for a character of `type` ("unknown clip 'run' for type 'dog'"),
/// or "" when it can. World refuses such a request with this message.
[[nodiscard]] std::string request_problem(const CharacterType& type, const RequestDesc& rd);

/// Every distinct problem of the requests and overlays of the scene's characters, crowd members
/// included, against `types` (types[i] for scene.types[i]; nullptr where the type failed to load
/// and is reported elsewhere). Each error names the scene file, the first character with the problem
/// and how many others share it.
[[nodiscard]] std::vector<Error> scene_request_problems(const SceneDesc& scene, const std::vector<const CharacterType*>& types);

}  // namespace aloha
