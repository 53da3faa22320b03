// Precomputed signed-power tables for tessellating super-ellipsoids at one (theta_steps,
// phi_steps) in the surface_grid layout, one table per distinct exponent pair (A, B). Built once
// per LOD level; the tessellation job only reads them.
#pragma once

#include "systems/geometry/muscle/muscle_set.hpp"

#include <glm/glm.hpp>

#include <cstdint>
#include <memory>
#include <span>
#include <vector>

namespace aloha {

/// Tables for one (T, P): for each exponent pair e and ring r in [1, P-1] the values
/// cos(phi)^A, sin(phi)^A, cos(phi)^(2-A), sin(phi)^(2-A); for each column t in [0, T) the values
/// cos(theta)^B, sin(theta)^B, cos(theta)^(2-B), sin(theta)^(2-B) (signed powers, computed in double).
class SuperEllipsoidTables {
public:
    /// Column/ring values of one exponent pair (spans into the table storage).
    struct View {
        std::span<const float> ring_cos, ring_sin, ring_ncos, ring_nsin;  ///< P-1 entries each
        std::span<const float> col_cos, col_sin, col_ncos, col_nsin;      ///< T entries each
    };

    /// Builds tables for (T, P) and every distinct pair in `set.exponents`. Requires T >= 3, P >= 2.
    SuperEllipsoidTables(uint32_t theta_steps, uint32_t phi_steps, const MuscleSet& set);

    /// Theta steps T.
    [[nodiscard]] uint32_t theta_steps() const { return t_; }
    /// Phi steps P.
    [[nodiscard]] uint32_t phi_steps() const { return p_; }
    /// Vertices per muscle grid, T*(P-1)+2.
    [[nodiscard]] uint32_t vertices_per_muscle() const;
    /// Number of muscles the tables were built for.
    [[nodiscard]] size_t muscle_count() const { return table_of_muscle_.size(); }
    /// Table view for muscle m. Requires m < muscle_count().
    [[nodiscard]] View muscle(size_t m) const { return view(table_of_muscle_[m]); }
    /// True when the tables were built for this set's exponents (same count and pairs).
    [[nodiscard]] bool matches(const MuscleSet& set) const;

private:
    [[nodiscard]] View view(uint32_t table) const;
    uint32_t t_ = 0, p_ = 0;
    std::vector<glm::vec2> pairs_;             // distinct (A, B) in first-seen order
    std::vector<uint32_t> table_of_muscle_;    // index into pairs_
    std::vector<float> data_;                  // per pair: 4*(P-1) ring values then 4*T column values
};

/// Owns tables for several (T, P) levels of one MuscleSet. Tables are built on first request
/// (allocation happens then, never again for that level); lookups scan a short list in insertion
/// order, so results are deterministic.
class SuperEllipsoidTableCache {
public:
    /// Cache for `set`, which must outlive the cache.
    explicit SuperEllipsoidTableCache(const MuscleSet& set) : set_(&set) {}
    /// Tables for (T, P), built if missing. Requires T >= 3, P >= 2.
    const SuperEllipsoidTables& get(uint32_t theta_steps, uint32_t phi_steps);
    /// Tables for (T, P) or nullptr when not built yet (never allocates).
    [[nodiscard]] const SuperEllipsoidTables* find(uint32_t theta_steps, uint32_t phi_steps) const;

private:
    const MuscleSet* set_;
    std::vector<std::unique_ptr<SuperEllipsoidTables>> levels_;
};

}  // namespace aloha
