// Carrying the fat springs' state from one frame's model space to the next (see fat_spring_frame.hpp).
#include "systems/geometry/spring_skin/fat_spring_frame.hpp"

#include <cassert>
#include <cmath>

namespace aloha {

SpringFrameChange spring_frame_change(const Transform& previous, const Transform& current, float dt) {
    SpringFrameChange out;
    if (previous.position == current.position && previous.rotation == current.rotation && previous.scale == current.scale) {
        out.moved = false;
        return out;
    }
    const glm::quat rel = glm::conjugate(current.rotation) * previous.rotation;  // R_cur^T R_prev
    const float w = std::min(1.0f, std::abs(rel.w) / std::max(1e-12f, glm::length(rel)));
    const float angle = 2.0f * std::acos(w);
    const float moved = glm::length(current.position - previous.position);
    const bool finite = std::isfinite(angle) && std::isfinite(moved);
    if (!finite || !(previous.scale > 0.0f) || !(current.scale > 0.0f) || !(dt > 0.0f) || moved > kSnapSpeed * dt ||
        angle > kSnapTurnRate * dt) {
        out.snapped = true;
        return out;
    }
    const glm::mat3 cur_t = glm::transpose(glm::mat3_cast(current.rotation));
    out.a = (previous.scale / current.scale) * glm::mat3_cast(glm::normalize(rel));
    out.b = cur_t * (previous.position - current.position) / current.scale;
    return out;
}

bool SpringReframeJob::Validate(std::vector<std::string>* errors) const {
    const size_t n = state.end.size();
    const bool ok = state.velocity.size() == n && state.prev_rest.size() == n;
    if (!ok && errors) errors->push_back("SpringReframeJob: end, velocity and prev_rest need the same size");
    return ok;
}

void SpringReframeJob::Run() const {
    assert(Validate());
    if (change.snapped || !change.moved) return;
    const glm::mat3 a = change.a;
    const glm::vec3 b = change.b;
    for (size_t i = 0; i < state.end.size(); ++i) {
        state.end[i] = a * state.end[i] + b;
        state.prev_rest[i] = a * state.prev_rest[i] + b;
        state.velocity[i] = a * state.velocity[i];
    }
}

}  // namespace aloha
