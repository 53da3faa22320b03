// Per character type geometry, built once at load and shared (read-only) by every geometric
// controller of that type: skeleton, muscle layout, rest pose, optional real skinned mesh, and lazily
// built per-tessellation data (super-ellipsoid tables, the per-muscle grid mesh, the skin layer with
// its muscle bindings, subdivision refinements, correspondences between skin resolutions), cached for
// the lifetime of the type.
#pragma once

#include "engine/anim/skeleton.hpp"
#include "engine/core/blob_store.hpp"
#include "engine/core/result.hpp"
#include "systems/geometry/muscle/muscle_set.hpp"
#include "systems/geometry/muscle/superellipsoid_tables.hpp"
#include "systems/geometry/body_skin/surface_map.hpp"
#include "systems/geometry/controller/skin_layer.hpp"
#include "systems/geometry/spring_skin/subdivision.hpp"

#include <glm/glm.hpp>
#include <glm/gtc/type_precision.hpp>

#include <array>
#include <cstdint>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <span>
#include <string>
#include <utility>
#include <vector>

namespace aloha {

/// A real skinned triangle mesh (e.g. from glTF), all primitives concatenated.
/// Skinning: v_model = sum_k w_k * model[joints_k] * inverse_bind[joints_k] * v.
struct CharacterMesh {
    std::vector<glm::vec3> positions;      ///< bind-space positions
    std::vector<glm::vec3> normals;        ///< bind-space unit normals, one per position
    std::vector<glm::u16vec4> joints;      ///< runtime skeleton joint indices, one per position
    std::vector<glm::vec4> weights;        ///< weights (sum 1), one per position
    std::vector<uint32_t> indices;         ///< triangle list
    std::vector<glm::mat4> inverse_bind;   ///< one per RUNTIME joint
    std::vector<glm::vec2> uvs;            ///< texture coordinates, one per position, or empty (none)
    std::vector<uint16_t> vertex_material; ///< material index per position (the type's list), or empty (all 0)
    std::vector<glm::vec4> colours;        ///< LINEAR RGBA multiplying the material, one per position, or empty (white)
};

/// The peeled (SkinnedMesh) bind mesh generated from the muscles of a type without a real mesh, at
/// one (T, P): vertex i of muscle m is the rest-pose muscle point plus the fat thickness along the
/// muscle normal (surface_grid layout, muscles concatenated). It is skinned to the joints from the
/// muscle's origin joint down to its insertion joint (at most 4), weighted smoothly by the vertex's
/// position u along the muscle axis: the cumulative weight past each pivot joint is
/// u a_i / (u a_i + (1 - u) a_o) with a_o, a_i the distances from the pivot to the two tendons, which
/// makes linear blending follow the straight origin-insertion muscle to first order in the rotation.
struct GeneratedBindMesh {
    uint32_t theta_steps = 0;               ///< T of the grids
    uint32_t phi_steps = 0;                 ///< P of the grids
    std::vector<glm::vec3> positions;       ///< rest-pose model space, muscles x V(T, P)
    std::vector<glm::vec3> normals;         ///< area-weighted skin normals at rest
    std::vector<glm::u16vec4> joints;       ///< origin .. insertion chain (runtime joint indices)
    std::vector<glm::vec4> weights;         ///< matching weights (sum 1)
};

/// What a character type is made of. `rest_model` empty = the skeleton's rest pose.
struct CharacterGeometryDesc {
    uint16_t type = 0;                       ///< the type id (CharacterRef::type), part of topology keys
    std::string name;                        ///< names the type in errors
    Skeleton skeleton;                       ///< runtime skeleton
    MuscleSet muscles;                       ///< resolved against `skeleton`; when empty only rigid-proxy
                                             ///< and (with a mesh) skinned-mesh levels may be used
    std::vector<glm::mat4> rest_model;       ///< rest-pose model matrix per joint (muscles rest here)
    std::optional<CharacterMesh> mesh;       ///< real skinned mesh, or none (generated body skin)
    float length_scale = 1.0f;               ///< body_length_scale of the type's standing height (skin_layer.hpp):
                                             ///< the body-skin build's lengths (grid cell, blend, binding spreads,
                                             ///< proxy radii's bounds) are this many times a person's; > 0
    /// Where the generated skin's load-time bakes (skin layers, maps between unrefined skins) are
    /// reused from and saved to (skin_bake.hpp); none: always built. Unused with a mesh.
    std::shared_ptr<const BlobStore> bake_cache;
};

/// One displayed surface of a type: its skin layer at (T, P) (the real mesh when the type has one: T
/// and P are then ignored) after `subdivision` Catmull-Clark steps (0: the skin layer itself).
struct SkinSurfaceKey {
    uint32_t theta_steps = 0;  ///< T of the skin layer
    uint32_t phi_steps = 0;    ///< P of the skin layer
    uint32_t subdivision = 0;  ///< Catmull-Clark steps (0..4)
    /// Keys order lexicographically (for the cache map).
    auto operator<=>(const SkinSurfaceKey&) const = default;
};

/// Immutable geometry of one character type plus thread-safe lazily built caches. Create with
/// CharacterGeometry::create; the object never moves (controllers keep pointers into it).
class CharacterGeometry {
public:
    /// Validates `desc` (muscles resolved for this skeleton, rest_model size, mesh sizes, joint
    /// indices in range, finite values) and builds the type: rest-pose mesh positions, per-joint proxy
    /// radii. Skin layers (and their muscle bindings) are built per tessellation on first use.
    /// Errors name desc.name and the problem.
    static Result<std::unique_ptr<CharacterGeometry>> create(CharacterGeometryDesc desc);

    CharacterGeometry(const CharacterGeometry&) = delete;
    CharacterGeometry& operator=(const CharacterGeometry&) = delete;

    /// Type id given at creation.
    [[nodiscard]] uint16_t type() const { return type_; }
    /// Name given at creation.
    [[nodiscard]] const std::string& name() const { return name_; }
    /// The skeleton.
    [[nodiscard]] const Skeleton& skeleton() const { return skeleton_; }
    /// Joint count of the skeleton.
    [[nodiscard]] uint32_t joint_count() const { return static_cast<uint32_t>(skeleton_.joint_count()); }
    /// The muscle layout.
    [[nodiscard]] const MuscleSet& muscles() const { return muscles_; }
    /// Muscle count.
    [[nodiscard]] uint32_t muscle_count() const { return static_cast<uint32_t>(muscles_.size()); }
    /// Rest-pose model matrices (one per joint).
    [[nodiscard]] std::span<const glm::mat4> rest_model() const { return rest_model_; }
    /// Inverse of each rest-pose model matrix (the palette base of the generated mesh).
    [[nodiscard]] std::span<const glm::mat4> inverse_rest_model() const { return inverse_rest_; }
    /// Box radius per joint for the rigid proxy (from the muscles along the bone, 0.04 m without).
    [[nodiscard]] std::span<const float> proxy_radii() const { return proxy_radii_; }
    /// True when the type has a real skinned mesh.
    [[nodiscard]] bool has_mesh() const { return mesh_.has_value(); }
    /// The real mesh. Requires has_mesh().
    [[nodiscard]] const CharacterMesh& mesh() const { return *mesh_; }
    /// The real mesh skinned at the rest pose (model space). Empty without a mesh.
    [[nodiscard]] std::span<const glm::vec3> mesh_rest_positions() const { return mesh_rest_positions_; }

    /// Super-ellipsoid tables at (T, P), built on first use. Thread-safe; the reference stays valid.
    /// Requires T >= 3, P >= 2.
    const SuperEllipsoidTables& tables(uint32_t theta_steps, uint32_t phi_steps) const;
    /// Generated peeled bind mesh at (T, P), built on first use. Thread-safe; stays valid.
    /// Requires T >= 3, P >= 2.
    const GeneratedBindMesh& generated_mesh(uint32_t theta_steps, uint32_t phi_steps) const;
    /// The skin layer at (T, P), built on first use (skin_layer.hpp): the generated body skin of a
    /// type without a mesh (the dense body surface is built once for all tessellations), the real mesh
    /// otherwise; bound to the muscles at (T, P). Thread-safe; stays valid. Requires muscles,
    /// T >= 3, P >= 2.
    const SkinLayer& skin_layer(uint32_t theta_steps, uint32_t phi_steps) const;
    /// Builds the skin layers at every (T, P) of `tessellations` that is not built yet, the generated
    /// ones with one simplification pass (simplify_and_relax_all: the cost of the coarsest alone; each
    /// layer equals what skin_layer() would build on its own). Thread-safe. Requires what skin_layer() does.
    void prepare_skin_layers(std::span<const std::pair<uint32_t, uint32_t>> tessellations) const;
    /// Catmull-Clark refinement of the skin at `level` (1..4): of the generated skin at (T, P) for a
    /// type without a mesh, of the real mesh's triangles (T, P ignored) otherwise. Thread-safe.
    const SubdivisionTopology& subdivision(uint32_t theta_steps, uint32_t phi_steps, uint32_t level) const;
    /// Correspondence from the generated skin at (T0, P0) to the one at (T1, P1) (surface_map.hpp),
    /// built on first use. Thread-safe; stays valid. Requires a type without a mesh.
    const SurfaceMap& skin_map(uint32_t from_theta, uint32_t from_phi, uint32_t to_theta, uint32_t to_phi) const;
    /// Rest-pose positions and triangles of the displayed surface `key` (the skin layer's, or the real
    /// mesh's, refined by the key's subdivision stencils). Allocates. Requires what skin_layer() and
    /// subdivision() do (a generated skin needs muscles).
    void rest_surface(SkinSurfaceKey key, std::vector<glm::vec3>& positions, std::vector<uint32_t>& indices) const;
    /// Correspondence from displayed surface `from` to displayed surface `to` at rest (closest points,
    /// surface_map.hpp): e.g. a Catmull-Clark refined skin read at a coarser skin's vertices, for
    /// geomorphs into and out of subdivided levels. Built on first use. Thread-safe; stays valid.
    const SurfaceMap& surface_map(SkinSurfaceKey from, SkinSurfaceKey to) const;
    /// simplify_indices(positions, indices, target_error).indices (simplified_indices.hpp), read from the bake cache
    /// when an earlier load saved the same inputs' result (keyed by their content). Thread-safe. Requires what
    /// simplify_indices() does.
    [[nodiscard]] std::vector<uint32_t> simplified(std::span<const glm::vec3> positions, std::span<const uint32_t> indices,
                                                   float target_error) const;
    /// Builds surface_map() for every (from, to) pair of `pairs` not built yet, the pairs in parallel,
    /// so a geomorph between those surfaces finds its map ready (no build at a level switch).
    /// Thread-safe. Requires what surface_map() does.
    void prepare_surface_maps(std::span<const std::pair<SkinSurfaceKey, SkinSurfaceKey>> pairs) const;

private:
    CharacterGeometry() = default;
    // The store skin layers are cached in: the bake cache for a generated body (keyed by bake_inputs_), else null.
    [[nodiscard]] const BlobStore* skin_layer_cache() const { return bake_inputs_.empty() ? nullptr : bake_cache_.get(); }
    // The skin layer at (T, P) from the bake cache, or null (no cache, no entry, a rejected entry).
    std::unique_ptr<SkinLayer> cached_skin_layer(uint32_t theta_steps, uint32_t phi_steps) const;
    // Saves a skin layer just built to the bake cache (when there is one).
    void save_skin_layer(const SkinLayer& layer) const;
    uint16_t type_ = 0;
    std::string name_;
    Skeleton skeleton_;
    MuscleSet muscles_;
    std::vector<glm::mat4> rest_model_, inverse_rest_;
    std::vector<float> proxy_radii_;
    float length_scale_ = 1.0f;                    // CharacterGeometryDesc::length_scale
    std::optional<CharacterMesh> mesh_;
    std::vector<glm::vec3> mesh_rest_positions_;
    std::shared_ptr<const BlobStore> bake_cache_;  // null: no cache; content-keyed entries suit any type
    std::vector<uint8_t> bake_inputs_;             // skin_bake_inputs of a generated body (with a cache); empty otherwise

    mutable std::mutex mutex_;
    mutable std::unique_ptr<SuperEllipsoidTableCache> table_cache_;
    mutable std::map<std::pair<uint32_t, uint32_t>, std::unique_ptr<GeneratedBindMesh>> generated_;
    mutable std::unique_ptr<BodySurface> body_surface_;
    mutable std::map<std::pair<uint32_t, uint32_t>, std::unique_ptr<SkinLayer>> skin_layers_;
    mutable std::map<std::array<uint32_t, 3>, std::unique_ptr<SubdivisionTopology>> subdivisions_;
    mutable std::map<std::pair<SkinSurfaceKey, SkinSurfaceKey>, std::unique_ptr<SurfaceMap>> surface_maps_;
};

/// Linear-blend skins `mesh` with palette model[j] * mesh.inverse_bind[j] (e.g. the rest pose, to get
/// model-space positions for muscle fitting). Requires model.size() == mesh.inverse_bind.size() and
/// valid joint indices.
[[nodiscard]] std::vector<glm::vec3> skin_mesh_positions(const CharacterMesh& mesh, std::span<const glm::mat4> model);

/// Builds the generated peeled bind mesh of `muscles` at the tables' (T, P) from the skeleton's
/// parents and rest-pose model matrices. Requires rest_model.size() == parents.size() ==
/// muscles.joint_count and tables built for `muscles`.
[[nodiscard]] GeneratedBindMesh build_generated_mesh(const MuscleSet& muscles, std::span<const int16_t> parents,
                                                     std::span<const glm::mat4> rest_model,
                                                     const SuperEllipsoidTables& tables);

}  // namespace aloha
