// Loads hand-written muscle layouts (data/characters/*_muscles.json, schema
// data/schemas/muscles.schema.json). Every error names the file, the line/column for syntax errors
// and the JSON path ("/muscles/4/origin/joint") for content errors.
#pragma once

#include "engine/anim/skeleton.hpp"
#include "engine/core/result.hpp"
#include "systems/geometry/muscle/muscle_set.hpp"

#include <nlohmann/json_fwd.hpp>

#include <string>
#include <string_view>
#include <vector>

namespace aloha {

/// The joint name on the other side of the body for CMU-style names: Left* <-> Right*,
/// L<Upper>* <-> R<Upper>* (LHipJoint, LFingers), lhand <-> rhand; other names are unchanged.
[[nodiscard]] std::string mirror_joint_name(std::string_view name);

/// Mirror image of `def` across the model's x = 0 plane: joints swapped with mirror_joint_name,
/// x of offsets and of the depth axis negated, named `mirror_name`. Valid for skeletons whose rest
/// joint frames are aligned with the model axes (BVH) and symmetric about x = 0.
[[nodiscard]] MuscleDef mirror_muscle(const MuscleDef& def, const std::string& mirror_name);

/// Parses muscle definitions from a parsed JSON document. Entries with "mirror" produce a second
/// definition right after the first. `source_name` names the file in errors.
Result<std::vector<MuscleDef>> parse_muscle_defs(const nlohmann::json& doc, const std::string& source_name);

/// Reads and parses `path` (syntax errors carry line and column).
Result<std::vector<MuscleDef>> load_muscle_defs(const std::string& path);

/// Scales a muscle layout written for one body to another: anchor offsets by `length` (height
/// ratio), rest radii by `length * girth` (volumes by length^3 * girth^2) and fat by `fat`.
/// Requires positive factors.
void scale_muscle_defs(std::vector<MuscleDef>& defs, float length, float girth, float fat);

/// Reads `path` and resolves it against `skeleton` at its rest pose (unknown joints, bad radii,
/// bad exponents etc. are errors naming the file and JSON path).
Result<MuscleSet> load_muscle_set(const std::string& path, const Skeleton& skeleton);

}  // namespace aloha
