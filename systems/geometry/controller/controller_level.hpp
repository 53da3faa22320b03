// Internal to the geometric controller: the shared data and storage of one level.
#pragma once

#include "systems/geometry/body_skin/surface_map.hpp"
#include "systems/geometry/controller/geometry_controller.hpp"
#include "systems/geometry/spring_skin/peeled.hpp"
#include "systems/geometry/spring_skin/strain_limit.hpp"
#include "systems/geometry/spring_skin/subdivision.hpp"

#include <cassert>

#include <atomic>
#include <span>
#include <vector>

namespace aloha {

/// One level: its parameters, what its method reads (tables, bind mesh, refinement, index buffer)
/// and the slots of its characters.
struct GeometryController::Level {
    GeomLod lod;                                   ///< parameters from the rule file
    uint8_t index = 0;                             ///< position in the level table
    uint8_t revision = 0;                          ///< bumped when set_levels rebuilds the level
    bool mesh_level = false;                       ///< SkinnedMesh, Layered or Subdivided
    bool real_mesh = false;                        ///< the control surface is the real mesh
    bool keep_refined = true;                      ///< Subdivided: refined surface kept per slot
    uint32_t theta_steps = 0, phi_steps = 0;       ///< grid tessellation (muscles, grid skin)
    uint32_t grid_vertices = 0;                    ///< V(T, P) (vertices per muscle)
    uint32_t control_vertices = 0;                 ///< control surface vertices per character
    uint32_t display_vertices = 0;                 ///< displayed vertices per character
    const SuperEllipsoidTables* tables = nullptr;  ///< Layered / Subdivided
    const SkinLayer* skin = nullptr;               ///< skin layer (types with muscles, mesh levels)
    bool springs = false;                          ///< fat springs run (Layered / Subdivided with the fat layer)
    std::vector<uint8_t> spring_region;            ///< per control vertex: its fat region (fat_regions.hpp); empty: none
    const SubdivisionTopology* subdivision = nullptr;  ///< Subdivided
    SkinSurfaceKey display_key;                    ///< the displayed surface (mesh levels): geomorph correspondences
    std::span<const uint32_t> indices;             ///< the level's triangle list
    std::vector<uint32_t> simplified_indices;      ///< SkinnedMesh with simplify_error: the list `indices` shows
    /// With simplified_indices: every vertex located at rest on the simplified triangles (its closest point;
    /// a vertex the list keeps is its own), so the fidelity deviation reads a vertex the list leaves out where
    /// the drawn surface shows that part of the body. Empty otherwise.
    SurfaceMap simplified_map;
    SkinEdges control_edges;                       ///< mesh levels: the control surface's edges (strain limiting)
    SkinEdges refined_edges;                       ///< Subdivided: the refined surface's edges
    std::vector<glm::vec2> uvs;                    ///< texture coordinate per displayed vertex (empty: none)
    std::vector<glm::vec4> colours;                ///< linear colour per displayed vertex (empty: white)
    std::vector<uint16_t> vertex_material;         ///< material per displayed vertex (empty: all 0)
    SlotStore store;                               ///< per-character storage
    std::atomic<uint64_t> work_characters{0};      ///< GeometryWork::characters
    std::atomic<uint64_t> work_springs{0};         ///< GeometryWork::springs_stepped
    std::atomic<uint64_t> work_vertices{0};        ///< GeometryWork::skin_vertices

    /// Level with storage shaped by `layout`.
    explicit Level(const SlotLayout& layout) : store(layout) {}

    /// True when `other` displays the same control vertices (same mesh, or same generated skin).
    [[nodiscard]] bool same_skin(const Level& other) const {
        return real_mesh || (theta_steps == other.theta_steps && phi_steps == other.phi_steps);
    }
    /// True when the level runs muscles (Layered / Subdivided).
    [[nodiscard]] bool layered() const {
        return lod.method == GeomMethod::Layered || lod.method == GeomMethod::Subdivided;
    }
    /// The shown control surface of slot `s`: the placed skin (spring ends with the fat layer) strain
    /// limited, morphed while a switch morphs. A Subdivided level morphs after refinement, so its
    /// control surface is never the morphed one.
    [[nodiscard]] std::span<const glm::vec3> control(uint32_t s) const { return store.positions(s); }
};

/// Points `job`'s bind inputs at the mesh `level` skins: the type's real mesh, or the level's generated
/// skin layer.
inline void set_lbs_source(const CharacterGeometry& g, const GeometryController::Level& level, LinearBlendSkinJob& job) {
    if (level.real_mesh) {
        job.bind_positions = g.mesh().positions;
        job.bind_normals = g.mesh().normals;
        job.joints = g.mesh().joints;
        job.weights = g.mesh().weights;
    } else {
        job.bind_positions = level.skin->rest_positions;
        job.bind_normals = level.skin->rest_normals;
        job.joints = level.skin->joints;
        job.weights = level.skin->weights;
    }
}

/// The displayed surface of the Subdivided level `L`: `control` refined into `refined` (and `normals`
/// when given), then, when `strain_limited`, its edges limited (strain_limit.hpp). True when the limit
/// moved it (normals given are then stale). Requires L.subdivision and sizes that match it.
inline bool refine_displayed(const GeometryController::Level& L, std::span<const glm::vec3> control, std::span<glm::vec3> refined,
                             std::span<glm::vec3> normals = {}, bool strain_limited = true) {
    const SubdivideJob refine{L.subdivision, control, refined, normals};
    assert(refine.Validate());
    refine.Run();
    return strain_limited && limit_skin_strain(L.refined_edges, refined, kRefinedStrainIterations);
}

/// True when two parameter sets give the same storage and topology (method, T, P, subdivision).
[[nodiscard]] bool same_level_shape(const GeomLod& a, const GeomLod& b);

}  // namespace aloha
