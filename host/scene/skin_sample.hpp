// One character's displayed body as the last frame left it, in world space, for exporting and
// inspecting the deformed skin (aloha export --out FILE.glb): the triangles its geometric level draws
// (the mesh levels' skin, or the rigid proxy's boxes) and its skeleton at that frame's pose.
#pragma once

#include "components/lod.hpp"

#include <glm/glm.hpp>

#include <cstdint>
#include <string>
#include <vector>

namespace aloha {

/// Filled by World::skin_sample; reuse one across calls to keep its storage.
struct SkinSample {
    uint16_t type = 0;                     ///< character type index
    uint32_t id = 0;                       ///< id within the type
    uint8_t level = 0xFF;                  ///< geometric level shown (0xFF: none yet)
    GeomMethod method = GeomMethod::Hidden;  ///< how that level is drawn for this type
    std::vector<glm::vec3> positions;      ///< displayed vertices, world space (metres)
    std::vector<glm::vec3> normals;        ///< unit normals, same size
    std::vector<uint32_t> indices;         ///< triangle list into positions
    std::vector<std::string> joint_names;  ///< skeleton order
    std::vector<int16_t> parents;          ///< parent joint per joint, -1 for roots (parents[j] < j)
    std::vector<glm::mat4> joints;         ///< every joint's world matrix at this frame's pose
    glm::mat4 placement{1.0f};             ///< the character's root placement (world_matrix of its Transform)
};

}  // namespace aloha
