// Joint-limit tables: per-joint Euler-angle ranges read from JSON (data/characters/*_limits.json,
// schema data/schemas/joint_limits.schema.json) and applied to a Skeleton by joint name.
//
// File format: {"units": "degrees" | "radians" (default degrees), "euler_order": "XYZ" (optional,
// only XYZ), "joints": {"<name>": {"min": [x, y, z], "max": [x, y, z]}, ...}} plus optional
// "$schema" / "description" strings. Angles are the XYZ-intrinsic Euler angles of the joint's local
// rotation relative to its rest pose (JointLimit's convention), |angle| <= 180 degrees, min <= max.
#pragma once

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

}  // namespace aloha
