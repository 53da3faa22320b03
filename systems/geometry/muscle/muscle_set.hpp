// Muscle layout of one character type: editable definitions (joint names, metres) and the
// resolved structure-of-arrays MuscleSet (joint indices, rest volume, ratio, exponents) that the
// shape and tessellation jobs read.
#pragma once

#include "engine/anim/skeleton.hpp"
#include "engine/core/result.hpp"

#include <glm/glm.hpp>

#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

namespace aloha {

/// One tendon attachment: a point fixed in a joint's (bone's) frame. The point is
/// joint origin + along * bone_vector + offset, where bone_vector is the translation of the
/// joint's first child with non-zero length (the bone "points along its child OFFSET").
struct MuscleAnchor {
    std::string joint;             ///< joint (bone) name in the skeleton
    float along = 0.0f;            ///< fraction of the bone's length along the bone (0 = at the joint)
    glm::vec3 offset{0.0f};        ///< metres, in the joint's frame
};

/// Fat-spring dynamics of one body region (the layout file's "fat_regions"): each value given
/// overrides the geometric controller's tuning (FatSpringParams) for the skin over the region's
/// muscles; an absent value keeps the controller's.
struct FatRegion {
    std::string name;                     ///< region name ("belly", "thigh", ...)
    std::optional<float> normal_hz;       ///< natural frequency along the spring (Hz, stiffness)
    std::optional<float> normal_damping;  ///< damping ratio along the spring (1 = critical)
    std::optional<float> lateral_hz;      ///< frequency of the critically damped lateral follow (Hz)
    std::optional<float> max_strain;      ///< strain limit (fraction of the fat thickness)
};

/// Most fat regions one layout may name (the controller keeps one spring stepper per region).
inline constexpr size_t kMaxFatRegions = 15;

/// A muscle as written by hand. Give either rest radii (width ry, depth rz at the rest pose, the
/// length comes from the skeleton) or a rest volume with the ratio p = ry / rz.
struct MuscleDef {
    std::string name;
    MuscleAnchor origin;           ///< tendon nearest the spine
    MuscleAnchor insertion;        ///< other tendon
    glm::vec2 rest_radii{0.0f};    ///< (ry width, rz depth) in metres at rest; (0,0) = use volume + ratio
    float volume = 0.0f;           ///< m^3, used when rest_radii is (0,0)
    float ratio = 1.0f;            ///< p = ry / rz, used with volume
    float exponent_a = 1.0f;       ///< A (phi exponent), in [kMinSuperExponent, kMaxSuperExponent]
    float exponent_b = 1.0f;       ///< B (theta exponent), same range
    float fat_thickness = 0.005f;  ///< metres of fat over this muscle (read by the fat-spring layer)
    glm::vec3 depth_axis{0.0f};    ///< muscle z (depth) hint in the origin joint's frame; 0 = away from the bone
    std::optional<FatRegion> fat_region;  ///< the body region its fat belongs to (none: the controller's tuning)
    bool trunk_skin = false;       ///< its skin is the trunk's (a limb muscle over the shoulder girdle: the deltoid)
    std::string source_path;       ///< JSON path of the entry for errors ("" = "/muscles/<index>")
};

/// Resolved muscle layout for one skeleton (structure of arrays, one entry per muscle).
/// Invariants after resolve_muscles/fit: joints in range, volume/ratio > 0, valid exponents,
/// depth_hint unit length.
struct MuscleSet {
    int joint_count = 0;                      ///< joints of the skeleton it was resolved against
    std::vector<std::string> names;
    std::vector<int16_t> origin_joint;
    std::vector<int16_t> insertion_joint;
    std::vector<glm::vec3> origin_offset;     ///< metres in the origin joint's frame
    std::vector<glm::vec3> insertion_offset;  ///< metres in the insertion joint's frame
    std::vector<glm::vec3> depth_hint;        ///< unit vector in the origin joint's frame (muscle z)
    std::vector<float> volume;                ///< m^3, kept constant (eq. 5-8)
    std::vector<float> ratio;                 ///< p = ry / rz
    std::vector<glm::vec2> exponents;         ///< (A, B)
    std::vector<float> volume_factor;         ///< k(A, B) with V = k rx ry rz
    std::vector<float> fat_thickness;         ///< metres
    std::vector<float> rest_length;           ///< origin-insertion distance at the rest/bind pose (m)
    std::vector<uint8_t> fat_region;          ///< 0 = the controller's fat tuning, k = fat_regions[k - 1]
    std::vector<FatRegion> fat_regions;       ///< the regions the muscles name (at most kMaxFatRegions)
    std::vector<uint8_t> trunk_skin;          ///< 1: the generated skin joins it to the trunk's muscles, not its limb's

    /// Number of muscles.
    [[nodiscard]] int size() const { return static_cast<int>(names.size()); }
    /// Index of the muscle named `name`, or -1.
    [[nodiscard]] int find(const std::string& name) const;
    /// Appends one resolved muscle (all vectors grow by one). Requires valid values (see invariants).
    void push_back(const std::string& name, int origin, glm::vec3 origin_off, int insertion, glm::vec3 insertion_off,
                   glm::vec3 depth, float vol, float p, glm::vec2 ab, float fat, float length);
};

/// Rest-pose model matrices of `skeleton` (local rest transforms composed parent to child).
[[nodiscard]] std::vector<glm::mat4> rest_model_matrices(const Skeleton& skeleton);

/// The bone vector of joint j in its own frame: the rest translation of its first child with
/// non-zero length, or (0,0,0) when it has none.
[[nodiscard]] glm::vec3 bone_vector(const Skeleton& skeleton, int joint);

/// Resolves definitions against `skeleton`: joint names to indices, anchors to offsets, rest radii
/// to a volume using the rest pose (`rest_model`, or the skeleton's rest pose when empty).
/// Every problem (unknown joint, non-positive radii/volume/ratio, bad exponents, negative fat,
/// zero rest length, duplicate name) is reported with `source_name` and the path "/muscles/<i>/...".
/// Errors are collected; the first is returned and the rest appended to its message.
Result<MuscleSet> resolve_muscles(std::span<const MuscleDef> defs, const Skeleton& skeleton,
                                  const std::string& source_name, std::span<const glm::mat4> rest_model = {});

}  // namespace aloha
