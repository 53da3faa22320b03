// Joint-limit tables: per-joint Euler-angle ranges read from JSON (data/characters/*_limits.json,
// schema data/schemas/joint_limits.schema.json) and applied to a Skeleton by joint name.
//
// File format: {"units": "degrees" | "radians" (default degrees), "euler_order": "XYZ" (optional,
// only XYZ), "joints": {"<name>": {"min": [x, y, z], "max": [x, y, z]}, ...}} plus optional
// "$schema" / "description" strings. Angles are the XYZ-intrinsic Euler angles of the joint's local
// rotation relative to its rest pose (JointLimit's convention), |angle| <= 180 degrees, min <= max.
#pragma once

#include "engine/anim/humanoid_fit.hpp"
#include "engine/anim/humanoid_map.hpp"
#include "engine/anim/raw_skeleton.hpp"
#include "engine/anim/skeleton.hpp"
#include "engine/core/result.hpp"

#include <string>
#include <string_view>
#include <vector>

namespace aloha {

/// Joint limits by name, in radians, in the (sorted) key order of the file's "joints" object.
struct JointLimitTable {
    std::string source;               ///< file the table came from (for later errors)
    std::vector<std::string> names;   ///< joint names
    std::vector<JointLimit> limits;   ///< limits[i] for names[i]; limited == true, radians
};

/// Reads a joint-limit JSON file. Errors name the file, the line/column of JSON syntax errors
/// and the JSON path ("/joints/LeftKnee/min/1") of bad values.
Result<JointLimitTable> load_joint_limits(const std::string& path);

/// Parses joint-limit JSON `text`; `source_name` names it in errors.
Result<JointLimitTable> parse_joint_limits(std::string_view text, const std::string& source_name);

/// Sets the table's limits on `skeleton` (via set_joint_limits). Every name must be a joint of the
/// skeleton: an unknown name is an error naming it and its JSON path; nothing is changed then.
Status apply_joint_limits(Skeleton& skeleton, const JointLimitTable& table);

/// Sets the table's limits on a skeleton mapped to the canonical humanoid: a canonical name applies
/// to the joint `map` gives it (skipped when the skeleton lacks it, or when its rest bone is turned
/// more than 30 degrees from the reference humanoid's, e.g. a T-pose arm against the reference's
/// hanging arm, since the limits are relative to the rest pose); any other name must be a joint of
/// the skeleton. Requires a skeleton with model-aligned rest frames (normalise_rig) and `fit` from
/// fit_canonical. `skipped` receives "<canonical> (<angle> degrees)" for every entry left out for
/// its turned rest bone.
Status apply_mapped_joint_limits(Skeleton& skeleton, const JointLimitTable& table, const HumanoidMap& map,
                                 const CanonicalFit& fit, std::vector<std::string>* skipped);

}  // namespace aloha
