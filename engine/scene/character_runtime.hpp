// Per character type state the World keeps: the type's data, its motion controller (poses of all its
// characters) and per-character geometry buffers, plus the map from character id to group position.
#pragma once

#include "components/transform.hpp"
#include "engine/scene/character_type.hpp"

#include <glm/gtc/matrix_transform.hpp>
#include "systems/geometry/controller/geometry_controller.hpp"
#include "systems/motion/controller.hpp"
#include "systems/motion/dynamic/dynamic_hook.hpp"
#include "systems/motion/ik/ik_hooks.hpp"

#include <memory>
#include <vector>

namespace aloha {

/// World matrix of a character's root placement (translation * rotation * uniform scale).
inline glm::mat4 world_matrix(const Transform& t) {
    return glm::scale(glm::translate(glm::mat4(1.0f), t.position) * glm::mat4_cast(t.rotation), glm::vec3(t.scale));
}

/// Internal to the World: one per character type.
class CharacterRuntime {
public:
    /// Sets up the motion controller for `count` characters of `type` (ids 0..count-1); the
    /// geometric controller is made by init_geometry once the rule file's levels are known.
    CharacterRuntime(CharacterType type, uint32_t count);
    /// Builds the type's geometry and its geometric controller for `levels` (refined surfaces kept
    /// per character when `keep_refined_surfaces`). Errors name the type.
    Status init_geometry(uint16_t type_index, std::span<const GeomLod> levels, bool keep_refined_surfaces);
    /// `levels` as this type can draw them: a type without muscles (a non-humanoid) draws every
    /// skinned-mesh, layered and subdivided level with its own skinned mesh, or as rigid proxies
    /// when it has none.
    [[nodiscard]] std::vector<GeomLod> usable_levels(std::span<const GeomLod> levels) const;
    /// Where this type's pose matrices live, for GeometryController::update.
    [[nodiscard]] PoseSource poses() const;

    CharacterType type;
    std::unique_ptr<IkHookContext> ik;            ///< reach / look-at state (outlives `motion`)
    std::unique_ptr<DynamicHookContext> dynamics; ///< dynamic-walk simulations (outlives `motion`)
    std::unique_ptr<MotionController> motion;
    std::vector<uint32_t> element_of_character;  ///< id -> position in the World's group
    std::unique_ptr<CharacterGeometry> geometry_data;
    std::unique_ptr<GeometryController> geometry;
    std::vector<uint16_t> proxy_joints;          ///< joints drawn as proxy boxes (bones >= 5 cm)
    std::vector<std::string> path_names;         ///< scene path names added to `motion`, by path id
    std::vector<uint32_t> render_materials;      ///< renderer ids of type.materials (empty until registered)
    std::vector<int> feet;                       ///< ankles then toes of type.rig (empty without a rig)
    std::vector<glm::vec3> soles;                ///< each foot joint's sole point in its own frame
    uint32_t count = 0;
    uint32_t spawned = 0;

    /// Joints per character.
    [[nodiscard]] int joints() const { return type.skeleton.joint_count(); }
};

}  // namespace aloha
