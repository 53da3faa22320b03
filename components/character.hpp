// Plain data tying an entity to its character type and geometric resources.
#pragma once

#include <cstdint>

namespace aloha {

/// Which character type (skeleton + muscle layout + optional mesh) an entity uses.
struct CharacterRef {
    uint16_t type = 0;       ///< index into the scene's character library
    uint32_t id = 0;         ///< stable id within its type (index into the type's controllers)
};

/// Debug colour choice for rendering.
enum class DebugColour : uint8_t { Shaded = 0, ByLodLevel = 1, ByRule = 2, ByMotionMethod = 3 };

}  // namespace aloha
