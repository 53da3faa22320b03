// Internal part of the BVH loader: the HIERARCHY section parser. Used by bvh_loader.cpp.
#pragma once

#include "engine/anim/raw_skeleton.hpp"
#include "engine/assets/bvh_loader.hpp"
#include "engine/assets/text_scan.hpp"
#include "engine/core/result.hpp"

#include <cstdint>
#include <string>
#include <vector>

namespace aloha::bvh_detail {

/// One BVH channel kind.
enum class Channel : uint8_t { kXposition, kYposition, kZposition, kXrotation, kYrotation, kZrotation };

/// The parsed HIERARCHY: raw skeleton (metres) plus each raw joint's channels in file order.
struct Hierarchy {
    RawSkeleton skeleton;
    std::vector<std::vector<Channel>> channels;  ///< per raw joint (empty for kept End Sites)
    size_t total_channels = 0;                   ///< values per motion row
    int motion_line = 0;                         ///< line of the MOTION keyword
};

/// Reads lines from `cursor` up to and including the MOTION line and parses the hierarchy.
/// Errors name `file` and the line; requires options.unit_scale > 0.
Result<Hierarchy> parse_hierarchy(LineCursor& cursor, const std::string& file, const BvhOptions& options);

/// The channel's name as written in BVH files ("Xrotation").
const char* channel_name(Channel c);

}  // namespace aloha::bvh_detail
