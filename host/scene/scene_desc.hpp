// Plain description of a scene as read from a scene file: camera, character types, paths, placed
// characters, crowd generators, the rule file and the run length. Produced by load_scene().
#pragma once

#include "components/motion.hpp"

#include <glm/glm.hpp>

#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace aloha {

/// One camera keyframe: where the camera is and what it looks at, at `time` seconds.
struct CameraKey {
    float time = 0.0f;
    glm::vec3 position{0.0f, 1.7f, 10.0f};
    glm::vec3 target{0.0f, 1.0f, 0.0f};
};

/// A static camera (one key) or a keyframed path (linear interpolation, clamped at the ends).
struct CameraDesc {
    std::vector<CameraKey> keys;
    float fov_y_deg = 50.0f;
    float near_plane = 0.1f;
    float far_plane = 1000.0f;
};

/// A character type: a humanoid definition (the project's own humanoid, built for a height and
/// build, with its generated motion library), a BVH skeleton or a glTF file.
/// A motion file whose clips a character type plays, retargeted onto the type's skeleton through the canonical
/// humanoid (systems/motion/library/retarget.hpp). Exactly one of `bvh` and `gltf`.
struct MotionFileDesc {
    std::string bvh;    ///< absolute path of a BVH file (its motion is one clip)
    std::string gltf;   ///< absolute path of a glTF file (its animations are clips; its meshes are not used)
    std::string clip;   ///< glTF: the one animation to take by name ("" = every one)
    std::string name;   ///< the clip's name after the type's prefix ("" = the BVH file's stem, or the glTF animation's name)
    std::map<std::string, std::string> humanoid_map;  ///< canonical joint -> the file's joint name, as on a type
    float scale = 0.0f;  ///< metres per file unit (0 = detected from the skeleton's height)
    bool walk = false;   ///< also cut each clip to its best walk loop for the type's walk requests (as a type's own take is)
    std::string pointer; ///< JSON pointer of the entry ("/character_types/0/motions/1")
};

struct CharacterTypeDesc {
    std::string name;
    std::string humanoid;  ///< absolute path of a humanoid definition (data/characters/humanoid.json)
    std::string bvh;       ///< absolute path of a BVH skeleton (+ its motion as clip "<name>.mocap")
    std::string gltf;      ///< absolute path of a glTF character
    std::string muscles;   ///< absolute path of a muscle layout ("" = the definition's, or fit per bone)
    std::string limits;    ///< absolute path of joint limits ("" = the definition's, or free joints)
    float height = 1.75f;  ///< humanoid: standing height (m)
    float build = 0.5f;    ///< humanoid: 0 slim, 0.5 average, 1 heavy
    std::string clip_prefix;  ///< prefix of the type's clip names ("" = name); body variants share their base's
    std::map<std::string, std::string> humanoid_map;  ///< bvh/gltf: canonical joint -> file joint name (explicit map)
    float scale = 0.0f;       ///< bvh/gltf: metres per file unit (0 = detected from the skeleton's height)
    std::string canonical;    ///< bvh/gltf: the built-in humanoid definition, reference for mapped skeletons
    std::string scene_file;   ///< the scene file the type is written in (for errors)
    std::string pointer;      ///< JSON pointer of the type in that file ("/character_types/0")
    std::vector<MotionFileDesc> motions;  ///< clips from other files, retargeted (the type must be a mapped humanoid)
    bool generated_motion = true;  ///< bvh/gltf: a mapped humanoid also gets the generated motion library, retargeted
    std::vector<std::string> walks;  ///< bvh/gltf: the file's animations that are its walks ("" = every one that loops as one)
    std::string idle;              ///< the clip the type idles in (idlers, stance, impostors' standing row); "" = its own
                                   ///< choice (a file animation named like an idle, else the generated idle)
    float standing_height = 0.0f;  ///< bvh/gltf: a mapped humanoid scaled uniformly to stand this tall (m; a crowd's
                                   ///< height variants), 0 = as its file and `scale` make it
    std::string variant_of;        ///< a crowd's body variant: the JSON pointer of the range that made it ("/crowds/2/height");
                                   ///< "" for a type of the file's own
};

/// A named walk path: waypoints on the ground (y ignored), optionally looping.
struct PathDesc {
    std::string name;
    std::vector<glm::vec3> points;
    bool loop = true;
};

/// A request as written in the scene, resolved to ids at world build time.
struct RequestDesc {
    MotionRequest request;     ///< kind, timing, speed, target ...
    std::string clip;          ///< PlayClip: clip name
    std::string path;          ///< Walk: path name ("" = straight along request.target as a direction)
    std::vector<glm::vec3> route;  ///< Walk: a looping route of this character's own (a crowd's `walk_route`); beats `path`
    std::string effector;      ///< Reach/LookAt: joint name
};

/// One placed character.
struct CharacterDesc {
    int type = 0;              ///< index into SceneDesc::types
    glm::vec3 position{0.0f};
    float heading_deg = 0.0f;  ///< rotation about +Y
    float importance = 0.5f;
    bool always_full = false;  ///< the frame budget never demotes this character
    std::vector<RequestDesc> requests;
    std::optional<RequestDesc> overlay;  ///< reach / look-at layered over the requests (MotionController::set_overlay)
    float overlay_weight = 1.0f;         ///< its weight in [0, 1]
};

/// Mix of behaviours in a generated crowd (fractions, normalised at load).
struct CrowdMix {
    float walk = 0.6f;
    float idle = 0.3f;
    float reach = 0.1f;
};

/// Smallest circle a `circle` walker walks (m): one nearer the centre walks out to it first.
inline constexpr float kMinCircleRadius = 1.0f;
/// Waypoints of a generated circle route (a 22.5 degree turn at each).
inline constexpr int kCircleRouteWaypoints = 16;

/// A crowd generator: N characters on a grid or disc, deterministic from `seed`.
struct CrowdDesc {
    int type = 0;
    uint32_t count = 0;
    enum class Layout : uint8_t { Grid, Disc } layout = Layout::Grid;
    glm::vec3 center{0.0f};
    float spacing = 2.0f;          ///< grid spacing (m)
    float radius = 50.0f;          ///< disc radius (m)
    /// Where walkers go: straight along their heading forever, or each round the crowd's centre at
    /// its starting distance (at least kMinCircleRadius) on a looping route of its own.
    enum class WalkRoute : uint8_t { Straight, Circle } walk_route = WalkRoute::Straight;
    uint64_t seed = 1;
    CrowdMix mix;
    float importance_min = 0.1f, importance_max = 0.6f;
    float speed_min = 0.8f, speed_max = 1.6f;  ///< walking speed range (m/s)
    std::string clip;              ///< clip idle characters play ("" = the type's idle clip)
    float height_min = 0.0f, height_max = 0.0f;  ///< standing height range (m); 0 = the type's own
    float build_min = -1.0f, build_max = -1.0f;  ///< build range in [0, 1]; -1 = the type's own
    uint32_t variants = 0;         ///< body variants drawn from the ranges (0 = none: one body)
    std::vector<int> variant_types;  ///< types of the body variants (filled at load); each character picks one;
                                     ///< -1: one no character picked, dropped (drop_unused_variants)
};

/// A whole scene.
struct SceneDesc {
    std::string file;              ///< absolute path of the scene file
    std::string name;
    std::string rules;             ///< absolute path of the rule file
    std::string tier;              ///< hardware tier of the rules ("" = the rule file's default_tier, or auto)
    uint32_t frames = 300;
    float dt = 1.0f / 60.0f;
    uint32_t width = 1280, height = 720;
    CameraDesc camera;
    std::vector<CharacterTypeDesc> types;
    std::vector<PathDesc> paths;
    std::vector<CharacterDesc> characters;
    std::vector<CrowdDesc> crowds;
    uint64_t seed = 1;
};

/// Camera placement at time `t` (linear between keys, clamped at the ends). Requires keys non-empty.
CameraKey sample_camera(const CameraDesc& camera, float t);

/// A looping route round `center` through `start`'s distance from it (at least kMinCircleRadius, on
/// the ground plane of `center`): kCircleRouteWaypoints waypoints, the first one step ahead of
/// `start`, counter-clockwise seen from above for `turn` = 1, clockwise for -1.
std::vector<glm::vec3> circle_route(const glm::vec3& center, const glm::vec3& start, float turn);

/// Expands every crowd generator of `scene` into placed characters (deterministic for a seed) and
/// appends the explicitly placed ones first. `seed_override` != 0 replaces each crowd's seed.
std::vector<CharacterDesc> expand_characters(const SceneDesc& scene, uint64_t seed_override = 0);

/// Removes from `scene` the crowds' body variant types (CharacterTypeDesc::variant_of set) that no character of
/// `chars` (expand_characters(scene)) has, so nothing builds a body no one draws: the types after each removed one
/// move down, `chars`' types, the placed characters' and the crowds' follow, and a removed variant's entry in its
/// crowd's variant_types becomes -1 (expand_characters with the same seeds never picks it). Returns how many were
/// removed.
size_t drop_unused_variants(SceneDesc& scene, std::vector<CharacterDesc>& chars);

/// Total number of characters the scene will spawn.
uint64_t character_count(const SceneDesc& scene);

}  // namespace aloha
