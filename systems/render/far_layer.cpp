// Far layer planning (systems/render/far_layer.hpp).
#include "systems/render/far_layer.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>

namespace aloha {
namespace {

// The screen rectangle of a set of world spheres (Vulkan NDC), or the whole screen once one reaches the eye's plane.
class ScreenBound {
public:
    ScreenBound(const glm::mat4& clip_from_world, glm::vec2 scale) : clip_from_world_(clip_from_world), scale_(scale) {}

    void add(const glm::vec3& centre, float r) {
        if (whole_screen_) return;
        const glm::vec4 clip = clip_from_world_ * glm::vec4(centre, 1.0f);
        if (clip.w <= r) {  // the sphere reaches the eye's plane: no finite bound
            whole_screen_ = true;
            return;
        }
        // Over the sphere, clip x ranges over clip.x +- P00 r and w over w +- r (symmetric projection:
        // clip x = P00 * view x, w = the distance ahead); x / w lies between the extremes of those bounds.
        for (const float sx : {-1.0f, 1.0f})
            for (const float sw : {-1.0f, 1.0f}) {
                const glm::vec2 p = (glm::vec2(clip) + sx * r * scale_) / (clip.w + sw * r);
                lo_ = glm::min(lo_, p);
                hi_ = glm::max(hi_, p);
            }
    }

    // Padded by `pad` (NDC) and clamped to the screen.
    [[nodiscard]] glm::vec4 rect(glm::vec2 pad) const {
        if (whole_screen_) return glm::vec4(-1.0f, -1.0f, 1.0f, 1.0f);
        return glm::vec4(glm::clamp(lo_ - pad, -1.0f, 1.0f), glm::clamp(hi_ + pad, -1.0f, 1.0f));
    }

private:
    glm::mat4 clip_from_world_;
    glm::vec2 scale_;
    glm::vec2 lo_{1e30f}, hi_{-1e30f};
    bool whole_screen_ = false;
};

}  // namespace

void plan_far_layer(const FarLayerInput& in, FarLayerPlan& out) {
    out.runs.clear();
    out.mesh_splits.clear();
    out.far_count = 0;
    out.distant_count = 0;
    out.far_meshes = 0;
    const auto n = static_cast<uint32_t>(in.records.size());
    assert(in.order.size() == n);
    const bool enabled = in.focal_px > 0.0f && in.below_px > 0.0f;
    // NDC per unit of view-space x and y at distance 1 (the projection's P00 and P11).
    const glm::vec2 ndc_per_unit(2.0f * in.focal_px / in.viewport_width, 2.0f * in.focal_px / in.viewport_height);
    ScreenBound bound(in.clip_from_world, ndc_per_unit), distant_bound(in.clip_from_world, ndc_per_unit);
    const bool distant = enabled && in.distant_below_px > 0.0f;
    for (uint32_t first = 0; first < n;) {
        const uint32_t atlas = in.records[first].atlas;
        uint32_t end = first + 1;
        while (end < n && in.records[end].atlas == atlas) ++end;
        ImpostorRun run{first, end, end, atlas, end};
        if (enabled) {
            assert(atlas < in.layouts.size());
            const ImpostorAtlasLayout& layout = in.layouts[atlas];
            const float limit = in.focal_px * layout.height / in.below_px;
            const auto near = [&](uint32_t i) { return in.depth[i] <= limit || in.records[i].forward_phase.w < 1.0f; };
            const auto split = std::stable_partition(in.order.begin() + first, in.order.begin() + end, near);
            run.split = static_cast<uint32_t>(split - in.order.begin());
            // The far part is nearest first: its records beyond the distant limit are its tail.
            if (distant) {
                const float distant_limit = in.focal_px * layout.height / in.distant_below_px;
                run.distant = static_cast<uint32_t>(
                    std::partition_point(split, in.order.begin() + end, [&](uint32_t i) { return in.depth[i] <= distant_limit; }) -
                    in.order.begin());
            }
            const float tallest = impostor_quad_height(layout);  // every band's quad is centred on the pivot
            const float radius = 0.5f * std::sqrt(layout.width * layout.width + tallest * tallest);
            for (uint32_t k = run.split; k < end; ++k) {
                const glm::vec4& ps = in.records[in.order[k]].position_scale;
                (k < run.distant ? bound : distant_bound)
                    .add(glm::vec3(ps) + glm::vec3(0.0f, ps.w * (layout.bottom + 0.5f * layout.height), 0.0f), radius * ps.w);
            }
            out.far_count += run.distant - run.split;
            out.distant_count += end - run.distant;
        }
        out.runs.push_back(run);
        first = end;
    }
    const bool meshes = in.focal_px > 0.0f && in.meshes_below_px > 0.0f;
    for (const FarMeshGroup& g : in.mesh_groups) {
        assert(g.first + g.count <= in.mesh_order.size());
        uint32_t split = g.first + g.count;
        if (meshes) {
            // Near: at or behind the eye's plane, or at least meshes_below_px tall on screen.
            const auto near = [&](uint32_t m) {
                return in.mesh_depth[m] <= 0.0f || in.mesh_bounds[m].height * in.focal_px >= in.meshes_below_px * in.mesh_depth[m];
            };
            const auto begin = in.mesh_order.begin() + g.first;
            split = static_cast<uint32_t>(std::stable_partition(begin, begin + g.count, near) - in.mesh_order.begin());
            for (uint32_t k = split; k < g.first + g.count; ++k) {
                const glm::vec4& s = in.mesh_bounds[in.mesh_order[k]].sphere;
                bound.add(glm::vec3(s), s.w);
            }
            out.far_meshes += g.first + g.count - split;
        }
        out.mesh_splits.push_back(split);
    }
    out.far_count += out.far_meshes;
    // Two layer texels of padding (2 * divisor pixels, 4 * divisor / side in NDC): the bilinear filter reads one
    // texel beyond the quad's edge.
    const auto pad = [&](uint32_t divisor) { return 4.0f * float(divisor) / glm::vec2(in.viewport_width, in.viewport_height); };
    if (out.far_count > 0) out.ndc_rect = bound.rect(pad(kFarLayerDivisor));
    if (out.distant_count > 0) out.distant_ndc_rect = distant_bound.rect(pad(kDistantLayerDivisor));
}

}  // namespace aloha
