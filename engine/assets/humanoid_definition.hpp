// The project's own humanoid: a skeleton written as data (data/characters/humanoid.json, CMU/BVH
// joint names) whose segment lengths are fractions of standing height from a published
// anthropometric table, built here for any height and build.
#pragma once

#include "engine/anim/raw_skeleton.hpp"
#include "engine/core/result.hpp"

#include <string>
#include <vector>

namespace aloha {

/// Body proportions of one humanoid variant.
struct HumanoidBody {
    float height = 1.75f;  ///< standing height, metres (0.5 to 2.5)
    float build = 0.5f;    ///< 0 = slim, 0.5 = average, 1 = heavy (widths, muscle radii, fat)
};

/// A humanoid definition file as read: joints with offsets in units of standing height.
struct HumanoidDefinition {
    std::string file;               ///< absolute path it was read from
    RawSkeleton unit_skeleton;      ///< joint offsets in multiples of standing height, identity rest rotations
    std::vector<bool> lateral;      ///< per joint of unit_skeleton: x offset scales with build (widths)
    float reference_height = 1.75f; ///< height the muscle layout's metres are written for
    std::string muscles;            ///< absolute path of the muscle layout named by the file ("" = none)
    std::string limits;             ///< absolute path of the joint limits named by the file ("" = none)
};

/// Reads a humanoid definition. Errors name the file, the line/column (syntax) or JSON path.
Result<HumanoidDefinition> load_humanoid_definition(const std::string& path);

/// The skeleton of `def` for `body`: offsets scaled by height, lateral offsets (hip and shoulder
/// widths) by build. Rest rotations are identity (BVH convention: +X left, +Y up, +Z forward),
/// the root stands so the soles touch y = 0. Requires a definition from load_humanoid_definition.
[[nodiscard]] RawSkeleton humanoid_skeleton(const HumanoidDefinition& def, const HumanoidBody& body);

/// Checks `body` (finite, height in [0.5, 2.5] m, build in [0, 1]); errors name `source` and `where`.
Status validate_humanoid_body(const HumanoidBody& body, const std::string& source, const std::string& where);

}  // namespace aloha
