// What `aloha validate` prints about a character type: the humanoid mapping it found, the joints
// it ignores, the units and axes it assumed and the levels the character can use.
#pragma once

#include "host/scene/character_type.hpp"

#include <string>
#include <vector>

namespace aloha {

/// What a character type can do, in words: motion (clips, kinematic and dynamic walk, reach,
/// look-at) and geometric levels (proxy, skinned mesh, layered), each with the reason when refused.
[[nodiscard]] std::vector<std::string> character_capabilities(const CharacterType& type);

/// The report's lines for `type`: convention, "canonical <- file" pairs, ignored joints, units and
/// axes, capabilities (character_capabilities), then the type's notes.
[[nodiscard]] std::vector<std::string> character_report(const CharacterType& type);

}  // namespace aloha
