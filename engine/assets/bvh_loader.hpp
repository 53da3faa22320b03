// BVH (Biovision Hierarchy) motion-capture loader: skeleton from HIERARCHY, clip from MOTION.
//
// Conventions:
// - Rest pose: each joint's OFFSET (times unit_scale) with identity rotation and unit scale.
// - Rotation channels are degrees applied in the listed order, intrinsically: "Zrotation
//   Xrotation Yrotation" gives q = qZ * qX * qY (a vector in the joint's frame is rotated by qY
//   first). Orders may differ per joint.
// - Position channels REPLACE the OFFSET on the axes they name (CMU roots have OFFSET 0 0 0);
//   axes without a position channel keep the OFFSET value. Joints with a position channel get a
//   translation track; every joint with a rotation channel gets a rotation track; no scale tracks.
// - Key k is at time k * frame_time; duration = (frame_count - 1) * frame_time; start_offset = 0.
//   A skeleton-only file ("Frames: 0", whose Frame Time may be 0) gets one key at 0 holding the rest
//   pose, with a note.
// - Tracks are in RUNTIME order (see animation_remap.hpp); for BVH, raw and runtime order coincide
//   because the file lists joints depth-first with parents first.
// - End Sites are not joints unless keep_end_sites; kept ones are named "<parent>_End".
#pragma once

#include "engine/anim/raw_animation.hpp"
#include "engine/anim/raw_skeleton.hpp"
#include "engine/core/result.hpp"

#include <string>
#include <string_view>
#include <vector>

namespace aloha {

/// Options for reading BVH files.
struct BvhOptions {
    float unit_scale = 0.056444f;  ///< file units -> metres (CMU: 1 unit = 0.056444 m); must be > 0
    bool keep_end_sites = false;   ///< add End Sites as channel-less leaf joints
};

/// A BVH file's skeleton and clip.
struct BvhData {
    RawSkeleton skeleton;    ///< joints in file order (parents first)
    RawAnimation animation;  ///< one clip named after the file stem; tracks in runtime joint order
    float frame_time = 0.0f; ///< seconds per frame ("Frame Time")
    int frame_count = 0;     ///< number of frames ("Frames"); 0 for a skeleton-only file (its clip: one rest-pose key)
    std::vector<std::string> notes;  ///< what was read differently from a take (a skeleton-only file)
};

/// Most frames a BVH may declare; larger "Frames" values are refused before allocating.
inline constexpr int64_t kMaxBvhFrames = 10'000'000;

/// Reads and parses the BVH file at `path`. Errors name the file, the line and the problem.
Result<BvhData> load_bvh(const std::string& path, const BvhOptions& options = {});

/// Parses BVH `text`; `source_name` is used in errors and (its stem) as the clip name.
Result<BvhData> parse_bvh(std::string_view text, const std::string& source_name, const BvhOptions& options = {});

}  // namespace aloha
