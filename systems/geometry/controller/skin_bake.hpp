// The load-time bakes of a generated body kept in the bake cache (engine/core/blob_store.hpp): the
// skin layer at each tessellation (the body surface simplified, relaxed and bound to the muscles, the
// costly part of creating a character type) and the correspondences between unrefined skins.
//
// An entry's key is its kind and parameters plus everything the bake reads of the type (bake_inputs:
// the muscle set, the skeleton's parents, the rest-pose matrices, the proxy radii); the store adds the
// code version (skin_bake_code_version). The payload is the structure's vectors in plain little-endian
// binary (byte_io.hpp), read back bit for bit.
#pragma once

#include "engine/anim/skeleton.hpp"
#include "engine/core/blob_store.hpp"
#include "engine/core/byte_io.hpp"
#include "engine/core/result.hpp"
#include "systems/geometry/body_skin/surface_map.hpp"
#include "systems/geometry/controller/skin_layer.hpp"
#include "systems/geometry/muscle/muscle_set.hpp"

#include <glm/glm.hpp>

#include <cstdint>
#include <optional>
#include <span>
#include <vector>

namespace aloha {

/// The code version of the bakes: the digest of the library's sources and of how they were built (kBakeCodeDigest:
/// compiler, flags, configuration, header libraries), then the GNU build-ids of the shared libraries the bakes call —
/// libmeshoptimizer (vertex-cache order) and libm (exp, pow, trigonometry: not correctly rounded, so a C library
/// update may change bits). Every program built from the same sources the same way (a game relinked after an edit of
/// its own code, the tool, each test program) has the same version and reads the others' bakes; an edit of the
/// library's code, a new compiler, other flags or another library build gives a new version, and an old entry is
/// never read again. Computed once per process. Errors: a shared library without a build-id (the cache is then off).
[[nodiscard]] Result<std::vector<uint8_t>> skin_bake_code_version();

/// The key bytes of everything a generated body's bakes read of its type (its length scale: CharacterGeometryDesc).
[[nodiscard]] std::vector<uint8_t> skin_bake_inputs(const MuscleSet& muscles, std::span<const int16_t> parents,
                                                    std::span<const glm::mat4> rest_model, std::span<const float> proxy_radii,
                                                    float length_scale);

/// The key of the skin layer at (T, P) of the type whose bake_inputs are `inputs`.
[[nodiscard]] std::vector<uint8_t> skin_layer_key(std::span<const uint8_t> inputs, uint32_t theta_steps, uint32_t phi_steps);

/// The key of the surface map that locates `target` on the triangles (source, source_indices): a 128-bit digest
/// of exactly what map_surface reads, so any two surfaces (refined or not, generated or imported) that give
/// the same map share an entry, and nothing else can change it.
[[nodiscard]] std::vector<uint8_t> surface_map_key(std::span<const glm::vec3> source, std::span<const uint32_t> source_indices,
                                                   std::span<const glm::vec3> target);

/// The key of simplify_indices' result for these inputs: a 128-bit digest of the positions, the triangles and the
/// error bound (their bits).
[[nodiscard]] std::vector<uint8_t> simplified_indices_key(std::span<const glm::vec3> positions, std::span<const uint32_t> indices,
                                                          float target_error);

/// A triangle list's payload bytes (simplified_indices_key's entries).
[[nodiscard]] std::vector<uint8_t> write_triangle_list(std::span<const uint32_t> indices);
/// Reads a triangle list's payload; nothing when the bytes are not one complete list of whole triangles over
/// `vertices` vertices.
[[nodiscard]] std::optional<std::vector<uint32_t>> read_triangle_list(std::span<const uint8_t> bytes, size_t vertices);

/// A skin layer's payload bytes.
[[nodiscard]] std::vector<uint8_t> write_skin_layer(const SkinLayer& layer);
/// Reads a skin layer's payload; nothing when the bytes are not one complete, consistent layer
/// (sizes per vertex agree, indices and influences in range for `muscle_count` muscles).
[[nodiscard]] std::optional<SkinLayer> read_skin_layer(std::span<const uint8_t> bytes, uint32_t muscle_count);

/// A surface map's payload bytes.
[[nodiscard]] std::vector<uint8_t> write_surface_map(const SurfaceMap& map);
/// Reads a surface map's payload; nothing when the bytes are not one complete map over
/// `source_vertices` source vertices with `target_vertices` targets.
[[nodiscard]] std::optional<SurfaceMap> read_surface_map(std::span<const uint8_t> bytes, size_t source_vertices,
                                                         size_t target_vertices);

}  // namespace aloha
