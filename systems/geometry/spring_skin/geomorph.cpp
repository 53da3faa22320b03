// Geomorphing between grid tessellations (see geomorph.hpp).
#include "systems/geometry/spring_skin/geomorph.hpp"

#include "systems/geometry/spring_skin/grid_sample.hpp"

#include <algorithm>

namespace aloha {

bool GeomorphBeginJob::Validate(std::vector<std::string>* errors) const {
    bool ok = true;
    auto fail = [&](std::string message) {
        ok = false;
        if (errors) errors->push_back("GeomorphBeginJob: " + std::move(message));
    };
    const bool old_ok = old_theta_steps >= 3 && old_phi_steps >= 2, new_ok = new_theta_steps >= 3 && new_phi_steps >= 2;
    if (!old_ok) fail("old tessellation needs T >= 3 and P >= 2");
    if (!new_ok) fail("new tessellation needs T >= 3 and P >= 2");
    if (old_ok && new_ok) {
        const size_t vo = grid_vertex_count(old_theta_steps, old_phi_steps);
        const size_t vn = grid_vertex_count(new_theta_steps, new_phi_steps);
        if (old_positions.size() % vo != 0) fail("old_positions is not a whole number of old grids");
        if (new_positions.size() % vn != 0) fail("new_positions is not a whole number of new grids");
        if (old_positions.size() / vo != new_positions.size() / vn) fail("old and new surfaces hold different grid counts");
    }
    if (deltas.size() != new_positions.size()) fail("deltas size differs from new_positions");
    return ok;
}

void GeomorphBeginJob::Run() const {
    assert(Validate());
    const uint32_t vo = grid_vertex_count(old_theta_steps, old_phi_steps);
    const uint32_t vn = grid_vertex_count(new_theta_steps, new_phi_steps);
    // Parameters of the new vertices are the same for every grid: compute each once per grid pass.
    const size_t grids = new_positions.size() / vn;
    for (uint32_t i = 0; i < vn; ++i) {
        const GridParam param = grid_vertex_param(new_theta_steps, new_phi_steps, i);
        for (size_t g = 0; g < grids; ++g) {
            const glm::vec3 old_point = sample_grid(old_positions.subspan(g * vo, vo), old_theta_steps, old_phi_steps, param);
            deltas[g * vn + i] = old_point - new_positions[g * vn + i];
        }
    }
}

bool GeomorphJob::Validate(std::vector<std::string>* errors) const {
    bool ok = true;
    auto fail = [&](std::string message) {
        ok = false;
        if (errors) errors->push_back("GeomorphJob: " + std::move(message));
    };
    if (vertices_per_character == 0) fail("vertices_per_character must be > 0");
    const size_t characters = frames_left.size();
    if (frames_total.size() != characters) fail("frames_total size differs from frames_left");
    if (positions.size() != characters * vertices_per_character) fail("positions must hold vertices_per_character per character");
    if (deltas.size() != positions.size()) fail("deltas size differs from positions");
    if (morphed.size() != positions.size()) fail("morphed size differs from positions");
    if (frames_total.size() == characters) {
        for (size_t c = 0; c < characters; ++c) {
            if (frames_left[c] > frames_total[c]) {
                fail("character " + std::to_string(c) + " has frames_left > frames_total");
                break;
            }
        }
    }
    return ok;
}

void GeomorphJob::Run() const {
    assert(Validate());
    const size_t n = vertices_per_character;
    for (size_t c = 0; c < frames_left.size(); ++c) {
        const auto src = positions.subspan(c * n, n);
        const auto dst = morphed.subspan(c * n, n);
        if (frames_left[c] == 0) {
            std::copy(src.begin(), src.end(), dst.begin());
            continue;
        }
        --frames_left[c];
        const float weight = static_cast<float>(frames_left[c]) / static_cast<float>(frames_total[c]);
        const auto d = deltas.subspan(c * n, n);
        for (size_t i = 0; i < n; ++i) dst[i] = src[i] + weight * d[i];
    }
}

}  // namespace aloha
