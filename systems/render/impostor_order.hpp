// Draw order nearest the camera first: mesh runs and the quads of each impostor atlas's run.
#pragma once

#include "systems/render/impostor_types.hpp"

#include <glm/glm.hpp>

#include <cstdint>
#include <span>
#include <vector>

namespace aloha {

/// Sorts `order` (indices into `depth`) nearest first, ties by index: the draw order of meshes and impostors.
void sort_nearest_first(std::span<uint32_t> order, std::span<const float> depth);

/// Fills `order` with the draw order of `impostors`: each run of equal atlas kept in place and sorted nearest
/// first along the view direction of `view` (ties by input order), `order[k]` the input index drawn k-th; and
/// `depth` with each input's distance ahead of the camera. Both are resized to the count (their capacity is
/// reused from call to call). Lavapipe tests depth before an alpha-tested fragment shader runs, so a near quad
/// drawn first spares the far quads' pixels it hides.
void sort_impostors_nearest_first(std::span<const ImpostorInstance> impostors, const glm::mat4& view, std::vector<uint32_t>& order,
                                  std::vector<float>& depth);

}  // namespace aloha
