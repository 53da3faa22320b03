// Characters grouped by (type, geometric level): the order the geometry and draw loops walk, so each
// level's work is one tight loop over its characters. Free of any ECS: the host passes its component
// spans, element e of each span being the same character.
//
// Index spaces: an *element* is a character's index in the host's component spans (refs[e], geom[e]);
// a *position* p in [0, size) walks the elements grouped: element order[p], character id ids[p].
// A host that keeps its spans sorted by group_keys() (the World partitions its ECS group) gets
// order[p] == p; a host with fixed storage (an array per component) walks `order`.
#pragma once

#include "components/character.hpp"
#include "components/lod.hpp"

#include <cstdint>
#include <span>
#include <vector>

namespace aloha {

/// The characters of one type at one geometric level: positions [begin, end) of CharacterGroups.
struct LevelRange {
    uint16_t type = 0;
    uint8_t level = 0;
    uint32_t begin = 0;
    uint32_t end = 0;
};

/// Characters grouped by (type, geometric level); see the file comment for the index spaces.
struct CharacterGroups {
    std::vector<uint32_t> keys;      ///< per element: level_group_key (group_keys fills it)
    std::vector<uint32_t> order;     ///< per position: element
    std::vector<uint32_t> ids;       ///< per position: the character's id in its type
    std::vector<LevelRange> ranges;  ///< runs of equal (type, level), in key order

    /// Number of characters grouped.
    [[nodiscard]] size_t size() const { return order.size(); }
    /// True when order[p] == p for every position (the host's spans are sorted by key).
    [[nodiscard]] bool in_place() const { return in_place_; }
    bool in_place_ = true;  ///< set by group_by_level
};

/// Sort key of a character: type in the high bits, geometric level in the low 8.
constexpr uint32_t level_group_key(uint16_t type, uint8_t level) { return uint32_t{type} << 8 | level; }

/// Fills `keys` (resized to refs.size()) with each element's level_group_key. Requires equal sizes.
void group_keys(std::span<const CharacterRef> refs, std::span<const GeomLod> geom, std::vector<uint32_t>& keys);

/// Groups the characters: fills out.keys, then out.order (stable by key), out.ids and out.ranges.
/// Linear when the elements are already sorted by key, else a stable sort. Requires equal sizes.
void group_by_level(std::span<const CharacterRef> refs, std::span<const GeomLod> geom, CharacterGroups& out);

}  // namespace aloha
