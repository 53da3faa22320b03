// One character type's controllers: the type's data, its motion controller (poses of all its
// characters) and geometric controller, plus the map from character id to the host's element. The
// World keeps one per type; a game with its own entity store can too (tests/install/consumer).
#pragma once

#include "components/transform.hpp"
#include "host/scene/character_bounds.hpp"
#include "host/scene/character_type.hpp"
#include "host/scene/scene_desc.hpp"
#include "systems/frame/draw_lists.hpp"
#include "systems/frame/geometry_frame.hpp"
#include "systems/frame/placement.hpp"
#include "systems/lod/rule_table.hpp"
#include "systems/geometry/controller/geometry_controller.hpp"
#include "systems/motion/controller.hpp"
#include "systems/motion/dynamic/dynamic_hook.hpp"
#include "systems/motion/ik/ik_hooks.hpp"
#include "engine/core/blob_store.hpp"

#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace aloha {

/// The rule table's geometric levels, in order (what init_geometry and GeometryController take).
std::vector<GeomLod> geom_levels(const RuleTable& table);

/// A scene character's placement (position, heading about +Y, unit scale).
Transform character_placement(const CharacterDesc& c);

/// One character type's controllers, for the World or any host.
class CharacterRuntime {
public:
    /// Sets up the motion controller for `count` characters of `type` (ids 0..count-1); the
    /// geometric controller is made by init_geometry once the rule file's levels are known.
    CharacterRuntime(CharacterType type, uint32_t count);
    /// Builds the type's geometry and its geometric controller for `levels` (refined surfaces kept
    /// per character when `keep_refined_surfaces`). Errors name the type.
    /// `bake_cache`: where the generated skin's load-time bakes are reused from (none: built).
    Status init_geometry(uint16_t type_index, std::span<const GeomLod> levels, bool keep_refined_surfaces,
                         std::shared_ptr<const BlobStore> bake_cache = nullptr);
    /// `levels` as this type can draw them: a type without muscles (a non-humanoid) draws every
    /// skinned-mesh, layered and subdivided level with its own skinned mesh (lit per pixel where it stands
    /// in for a layered or subdivided level: GeomLod::lit_per_pixel), or as rigid proxies when it has none
    /// (its impostor levels too: there is no surface to bake).
    [[nodiscard]] std::vector<GeomLod> usable_levels(std::span<const GeomLod> levels) const;
    /// Where this type's pose matrices live, for GeometryController::update.
    [[nodiscard]] PoseSource poses() const;
    /// The type's controller and poses for the frame glue's geometry stages (valid until `motion` changes).
    [[nodiscard]] GeometryType geometry_type() const { return {geometry.get(), poses()}; }
    /// What the frame glue's draw lists need of the type (valid while this runtime lives).
    [[nodiscard]] DrawType draw_type() const;
    /// Adds `scene`'s walk paths to the motion controller (path ids in scene order).
    void add_paths(const SceneDesc& scene);
    /// Measures `extent` (TypeExtent: rest pose and every clip key, and the skin beyond the joints: the
    /// mesh's, else the generated skin of the richest mesh level of `levels`, else 10% of the height)
    /// and sets type.radius to its body radius. Call after init_geometry.
    void measure_bounds(std::span<const GeomLod> levels);
    /// Bounds radius of scene character `c` of this type: the body radius, widened to what the IK chain
    /// of each of its reaches and look-ats (requests and overlay) can sweep. Requires measure_bounds().
    [[nodiscard]] float bounds_radius(const CharacterDesc& c) const;
    /// Queues scene character `index` (`c`, id `id` of this type): its requests and overlay, with clip,
    /// path and joint names resolved. Errors name the scene file, the character and the unknown name.
    Status queue_requests(const SceneDesc& scene, size_t index, const CharacterDesc& c, uint32_t id);

    CharacterType type;
    TypeExtent extent;                            ///< how far the type's joints and skin reach (measure_bounds)
    std::unique_ptr<IkHookContext> ik;            ///< reach / look-at state (outlives `motion`)
    std::unique_ptr<DynamicHookContext> dynamics; ///< dynamic-walk simulations (outlives `motion`)
    std::unique_ptr<MotionController> motion;
    std::vector<uint32_t> element_of_character;  ///< id -> the host's element (World: group position)
    std::unique_ptr<CharacterGeometry> geometry_data;
    std::unique_ptr<GeometryController> geometry;
    std::vector<uint16_t> proxy_joints;          ///< joints drawn as proxy boxes (bones >= 5 cm)
    std::vector<std::string> path_names;         ///< scene path names added to `motion`, by path id
    std::vector<int> feet;                       ///< ankles then toes of type.rig (empty without a rig)
    std::vector<glm::vec3> soles;                ///< each foot joint's sole point in its own frame
    uint32_t count = 0;
    uint32_t spawned = 0;

    /// Joints per character.
    [[nodiscard]] int joints() const { return type.skeleton.joint_count(); }
};

/// How make_character_runtimes builds the types.
struct TypeLoadOptions {
    unsigned threads = 1;                          ///< types built at once (0 = all cores); the result does not depend on it
    std::shared_ptr<const BlobStore> bake_cache;   ///< where generated skins' bakes are reused from (none: built)
};

/// One runtime per type of `scene`, sized for its characters in `chars` (expand_characters), with the
/// scene's paths and geometric controllers for `levels` (refined surfaces kept when
/// `keep_refined_surfaces`). The types are independent and built `load.threads` at a time. Errors name
/// the type's file and the problem (the first type's in scene order when several fail).
Result<std::vector<std::unique_ptr<CharacterRuntime>>> make_character_runtimes(const SceneDesc& scene,
                                                                               std::span<const CharacterDesc> chars,
                                                                               std::span<const GeomLod> levels,
                                                                               bool keep_refined_surfaces,
                                                                               const TypeLoadOptions& load = {});

/// The bake cache a host asked for: none when `enabled` is false; else the store over `dir` (default:
/// default_cache_directory()) for this build's code (skin_bake_code_version). When a shared library the bakes
/// call has no build-id, no directory is known, or the directory cannot be made or written: none, after one
/// message on standard error saying why. The store keeps its entries to `max_bytes` (0: no limit;
/// default: default_cache_limit_bytes(), $ALOHA_CACHE_MAX_MB or 1 GiB), least recently used removed first.
[[nodiscard]] std::shared_ptr<const BlobStore> open_bake_cache(bool enabled, const std::optional<std::string>& dir,
                                                               std::optional<uint64_t> max_bytes = std::nullopt);

}  // namespace aloha
