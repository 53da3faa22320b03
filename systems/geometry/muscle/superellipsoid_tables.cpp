#include "systems/geometry/muscle/superellipsoid_tables.hpp"

#include "systems/geometry/muscle/superellipsoid.hpp"
#include "systems/geometry/surface_grid.hpp"

#include <cassert>
#include <cmath>
#include <numbers>

namespace aloha {

SuperEllipsoidTables::SuperEllipsoidTables(uint32_t theta_steps, uint32_t phi_steps, const MuscleSet& set)
    : t_(theta_steps), p_(phi_steps) {
    assert(theta_steps >= 3 && phi_steps >= 2);
    table_of_muscle_.reserve(set.exponents.size());
    for (const glm::vec2 ab : set.exponents) {
        uint32_t k = 0;
        while (k < pairs_.size() && pairs_[k] != ab) ++k;
        if (k == pairs_.size()) pairs_.push_back(ab);
        table_of_muscle_.push_back(k);
    }
    const uint32_t rings = p_ - 1;
    const size_t stride = 4 * static_cast<size_t>(rings) + 4 * static_cast<size_t>(t_);
    data_.resize(stride * pairs_.size());
    const double pi = std::numbers::pi;
    for (size_t k = 0; k < pairs_.size(); ++k) {
        const double a = pairs_[k].x, b = pairs_[k].y;
        float* d = data_.data() + k * stride;
        for (uint32_t r = 0; r < rings; ++r) {
            const double phi = -pi / 2.0 + (r + 1) * pi / p_;
            const double c = std::cos(phi), s = std::sin(phi);
            d[r] = static_cast<float>(signed_pow(c, a));
            d[rings + r] = static_cast<float>(signed_pow(s, a));
            d[2 * rings + r] = static_cast<float>(signed_pow(c, 2.0 - a));
            d[3 * rings + r] = static_cast<float>(signed_pow(s, 2.0 - a));
        }
        float* col = d + 4 * rings;
        for (uint32_t t = 0; t < t_; ++t) {
            const double theta = -pi + t * 2.0 * pi / t_;
            // Exact zeros where cos/sin vanish analytically keep the grid symmetric.
            double c = std::cos(theta), s = std::sin(theta);
            if (std::fabs(c) < 1e-12) c = 0.0;
            if (std::fabs(s) < 1e-12) s = 0.0;
            col[t] = static_cast<float>(signed_pow(c, b));
            col[t_ + t] = static_cast<float>(signed_pow(s, b));
            col[2 * t_ + t] = static_cast<float>(signed_pow(c, 2.0 - b));
            col[3 * t_ + t] = static_cast<float>(signed_pow(s, 2.0 - b));
        }
    }
}

uint32_t SuperEllipsoidTables::vertices_per_muscle() const { return grid_vertex_count(t_, p_); }

bool SuperEllipsoidTables::matches(const MuscleSet& set) const {
    if (set.exponents.size() != table_of_muscle_.size()) return false;
    for (size_t m = 0; m < table_of_muscle_.size(); ++m)
        if (pairs_[table_of_muscle_[m]] != set.exponents[m]) return false;
    return true;
}

SuperEllipsoidTables::View SuperEllipsoidTables::view(uint32_t table) const {
    const size_t rings = p_ - 1;
    const size_t stride = 4 * rings + 4 * static_cast<size_t>(t_);
    const float* d = data_.data() + table * stride;
    const float* col = d + 4 * rings;
    View v;
    v.ring_cos = {d, rings};
    v.ring_sin = {d + rings, rings};
    v.ring_ncos = {d + 2 * rings, rings};
    v.ring_nsin = {d + 3 * rings, rings};
    v.col_cos = {col, t_};
    v.col_sin = {col + t_, t_};
    v.col_ncos = {col + 2 * t_, t_};
    v.col_nsin = {col + 3 * t_, t_};
    return v;
}

const SuperEllipsoidTables& SuperEllipsoidTableCache::get(uint32_t theta_steps, uint32_t phi_steps) {
    if (const SuperEllipsoidTables* t = find(theta_steps, phi_steps)) return *t;
    levels_.push_back(std::make_unique<SuperEllipsoidTables>(theta_steps, phi_steps, *set_));
    return *levels_.back();
}

const SuperEllipsoidTables* SuperEllipsoidTableCache::find(uint32_t theta_steps, uint32_t phi_steps) const {
    for (const auto& l : levels_)
        if (l->theta_steps() == theta_steps && l->phi_steps() == phi_steps) return l.get();
    return nullptr;
}

}  // namespace aloha
