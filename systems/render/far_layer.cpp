// Far layer planning (systems/render/far_layer.hpp).
#include "systems/render/far_layer.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>

namespace aloha {

void plan_far_layer(const FarLayerInput& in, FarLayerPlan& out) {
    out.runs.clear();
    out.far_count = 0;
    const auto n = static_cast<uint32_t>(in.records.size());
    assert(in.order.size() == n);
    const bool enabled = in.focal_px > 0.0f && in.below_px > 0.0f;
    glm::vec2 lo(1e30f), hi(-1e30f);
    bool whole_screen = false;
    // NDC per unit of view-space x and y at distance 1 (the projection's P00 and P11).
    const glm::vec2 scale(2.0f * in.focal_px / in.viewport_width, 2.0f * in.focal_px / in.viewport_height);
    for (uint32_t first = 0; first < n;) {
        const uint32_t atlas = in.records[first].atlas;
        uint32_t end = first + 1;
        while (end < n && in.records[end].atlas == atlas) ++end;
        ImpostorRun run{first, end, end, atlas};
        if (enabled) {
            assert(atlas < in.layouts.size());
            const ImpostorAtlasLayout& layout = in.layouts[atlas];
            const float limit = in.focal_px * layout.height / in.below_px;
            const auto near = [&](uint32_t i) { return in.depth[i] <= limit || in.records[i].forward_phase.w < 1.0f; };
            const auto split = std::stable_partition(in.order.begin() + first, in.order.begin() + end, near);
            run.split = static_cast<uint32_t>(split - in.order.begin());
            const float radius = 0.5f * std::sqrt(layout.width * layout.width + layout.height * layout.height);
            for (uint32_t k = run.split; k < end && !whole_screen; ++k) {
                const glm::vec4& ps = in.records[in.order[k]].position_scale;
                const glm::vec3 centre = glm::vec3(ps) + glm::vec3(0.0f, ps.w * (layout.bottom + 0.5f * layout.height), 0.0f);
                const glm::vec4 clip = in.clip_from_world * glm::vec4(centre, 1.0f);
                const float r = radius * ps.w;
                if (clip.w <= r) {  // the sphere reaches the eye's plane: no finite bound
                    whole_screen = true;
                    break;
                }
                // Over the sphere, clip x ranges over clip.x +- P00 r and w over w +- r (symmetric projection:
                // clip x = P00 * view x, w = the distance ahead); x / w lies between the extremes of those bounds.
                for (const float sx : {-1.0f, 1.0f})
                    for (const float sw : {-1.0f, 1.0f}) {
                        const glm::vec2 p = (glm::vec2(clip) + sx * r * scale) / (clip.w + sw * r);
                        lo = glm::min(lo, p);
                        hi = glm::max(hi, p);
                    }
            }
            out.far_count += end - run.split;
        }
        out.runs.push_back(run);
        first = end;
    }
    if (out.far_count == 0) return;
    if (whole_screen) {
        out.ndc_rect = glm::vec4(-1.0f, -1.0f, 1.0f, 1.0f);
        return;
    }
    // Two layer texels (four pixels) of padding: the bilinear filter reads one texel beyond the quad's edge.
    const glm::vec2 pad(8.0f / in.viewport_width, 8.0f / in.viewport_height);
    lo = glm::clamp(lo - pad, -1.0f, 1.0f);
    hi = glm::clamp(hi + pad, -1.0f, 1.0f);
    out.ndc_rect = glm::vec4(lo, hi);
}

}  // namespace aloha
