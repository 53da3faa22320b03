// Checks of a scene's requests against its loaded character types: what World would refuse when it
// queues them, found up front (aloha validate) with one error per distinct problem.
#pragma once

#include "engine/core/result.hpp"
#include "host/scene/character_type.hpp"
#include "host/scene/scene_desc.hpp"

#include <string>
#include <vector>

namespace aloha {

/// A request's names looked up on a character type, once: the clip of a play request, the effector joint of a
/// reach or look-at (-1 where the kind has none), or why it cannot be queued.
struct ResolvedRequest {
    std::string problem;  ///< "unknown clip 'run' for type 'dog'", "" when it can be queued
    int clip = -1;        ///< PlayClip: the clip's id in type.clips
    int effector = -1;    ///< Reach / LookAt: the joint
};

/// Request `rd` resolved for a character of `type`. World queues it with these ids, or refuses it with the problem.
[[nodiscard]] ResolvedRequest resolve_request(const CharacterType& type, const RequestDesc& rd);

/// Why request `rd` cannot be queued for a character of `type` (resolve_request's problem), or "" when it can.
[[nodiscard]] std::string request_problem(const CharacterType& type, const RequestDesc& rd);

/// Where scene `scene` asks for request `k` (or the overlay, when `overlay`) of character `index` of
/// expand_characters(scene): the JSON pointer of a placed character's request or overlay ("/characters/3/requests/1"),
/// or of the crowd key that made a crowd member's ("/crowds/0/clip" for its idlers, "/crowds/0/mix/reach" for its
/// reachers, who reach with a wrist; "/crowds/0" for its walkers).
[[nodiscard]] std::string request_place(const SceneDesc& scene, size_t index, const RequestDesc& rd, size_t k, bool overlay);

/// Every distinct problem of the requests and overlays of the scene's characters, crowd members
/// included, against `types` (types[i] for scene.types[i]; nullptr where the type failed to load
/// and is reported elsewhere). Each error names the scene file and the JSON pointer of the first placed character's
/// request or overlay with the problem ("/characters/3/requests/1") and how many others share it; a crowd member's
/// problem is named at the crowd key that asked for it ("/crowds/0/clip" for its idlers, "/crowds/0/mix/reach" for
/// its reachers, who reach with a wrist), one line per crowd.
[[nodiscard]] std::vector<Error> scene_request_problems(const SceneDesc& scene, const std::vector<const CharacterType*>& types);

}  // namespace aloha
