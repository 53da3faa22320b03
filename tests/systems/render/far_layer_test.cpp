// Far layer planning (systems/render/far_layer.hpp): which impostors and meshes go to the half-resolution layer
// (and which impostors on to the quarter-resolution distant layer),
// and the screen rectangle the composite covers.
#include "engine/gpu/lit_pipeline.hpp"
#include "systems/render/far_layer.hpp"

#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <utility>
#include <vector>

namespace aloha {
namespace {

// Camera at the origin looking down -Z, 60 degree vertical field of view, 1280 x 720.
struct View {
    glm::mat4 view = glm::lookAt(glm::vec3(0.0f), glm::vec3(0.0f, 0.0f, -1.0f), glm::vec3(0.0f, 1.0f, 0.0f));
    glm::mat4 proj = glm::perspective(glm::radians(60.0f), 1280.0f / 720.0f, 0.1f, 500.0f);
    glm::mat4 clip = gpu::vulkan_clip_from_gl() * proj * view;
    float focal_px = 0.5f * 720.0f * proj[1][1];  // 623.5 px per unit of height at distance 1
};

struct Records {
    std::vector<ImpostorInstance> records;
    std::vector<uint32_t> order;
    std::vector<float> depth;
    // One record at distance d ahead (x sideways), of `atlas`; records of one atlas must be added nearest first.
    void add(float d, float x, uint32_t atlas) {
        ImpostorInstance r;
        r.position_scale = glm::vec4(x, -0.9f, -d, 1.0f);
        r.atlas = atlas;
        records.push_back(r);
        order.push_back(static_cast<uint32_t>(order.size()));
        depth.push_back(d);
    }
};

FarLayerInput input_of(const View& v, Records& r, const std::vector<ImpostorAtlasLayout>& layouts) {
    FarLayerInput in;
    in.records = r.records;
    in.order = r.order;
    in.depth = r.depth;
    in.layouts = layouts;
    in.clip_from_world = v.clip;
    in.focal_px = v.focal_px;
    in.below_px = 70.0f;
    in.viewport_width = 1280.0f;
    in.viewport_height = 720.0f;
    return in;
}

TEST(FarLayer, EachRunsRecordsUnderTheLimitGoLastNearestFirst) {
    const View v;
    const std::vector<ImpostorAtlasLayout> layouts = {{16, 9, 1.0f, 0.0f, 1.8f}, {16, 9, 1.0f, 0.0f, 0.9f}};
    Records r;
    // A 1.8 m quad is under 70 px beyond 623.5 * 1.8 / 70 = 16.0 m; a 0.9 m one beyond 8.0 m.
    for (const float d : {5.0f, 10.0f, 15.9f, 16.2f, 40.0f}) r.add(d, 0.0f, 0);
    for (const float d : {5.0f, 7.9f, 8.1f, 30.0f}) r.add(d, 0.0f, 1);
    FarLayerPlan plan;
    plan_far_layer(input_of(v, r, layouts), plan);
    ASSERT_EQ(plan.runs.size(), 2u);
    EXPECT_EQ(plan.runs[0].first, 0u);
    EXPECT_EQ(plan.runs[0].split, 3u) << "16.2 m is the first 1.8 m record under 70 px";
    EXPECT_EQ(plan.runs[0].end, 5u);
    EXPECT_EQ(plan.runs[1].first, 5u);
    EXPECT_EQ(plan.runs[1].split, 7u) << "8.1 m is the first 0.9 m record under 70 px";
    EXPECT_EQ(plan.runs[1].atlas, 1u);
    EXPECT_EQ(plan.far_count, 4u);

    // A cross-fading record (its dither pairs with a mesh's at full resolution) stays at full resolution; the
    // run's far part keeps its order.
    Records fading = r;
    fading.records[3].forward_phase.w = -0.5f;
    FarLayerInput in = input_of(v, fading, layouts);
    plan_far_layer(in, plan);
    EXPECT_EQ(plan.runs[0].split, 4u);
    EXPECT_EQ(fading.order[3], 3u) << "the fading record joins the full-resolution part";
    EXPECT_EQ(fading.order[4], 4u);
    EXPECT_EQ(plan.far_count, 3u);

    in.below_px = 0.0f;  // off: every record at full resolution
    plan_far_layer(in, plan);
    EXPECT_EQ(plan.far_count, 0u);
    EXPECT_EQ(plan.runs[0].split, plan.runs[0].end);
}

// The distant layer: of each run's far part (nearest first), the records under distant_below_px go last into the
// quarter-resolution layer; each layer's rectangle holds its own records; 0 turns it off.
TEST(FarLayer, EachRunsFarRecordsUnderTheDistantLimitGoToTheDistantLayer) {
    const View v;
    const std::vector<ImpostorAtlasLayout> layouts = {{16, 9, 1.0f, 0.0f, 1.8f}, {16, 9, 1.0f, 0.0f, 0.9f}};
    Records r;
    // A 1.8 m quad is under 70 px beyond 16.0 m and under 30 px beyond 623.5 * 1.8 / 30 = 37.4 m; a 0.9 m one
    // beyond 8.0 and 18.7 m. The distant records stand 8 m to the right, the far ones at the centre or left of it.
    for (const float d : {5.0f, 16.2f, 37.0f, 37.8f, 60.0f}) r.add(d, d > 37.4f ? 8.0f : -3.0f, 0);
    for (const float d : {5.0f, 8.1f, 18.9f}) r.add(d, d > 18.7f ? 8.0f : 0.0f, 1);
    FarLayerInput in = input_of(v, r, layouts);
    in.distant_below_px = 30.0f;
    FarLayerPlan plan;
    plan_far_layer(in, plan);
    ASSERT_EQ(plan.runs.size(), 2u);
    EXPECT_EQ(plan.runs[0].split, 1u);
    EXPECT_EQ(plan.runs[0].distant, 3u) << "37.8 m is the first 1.8 m record under 30 px";
    EXPECT_EQ(plan.runs[1].split, 6u);
    EXPECT_EQ(plan.runs[1].distant, 7u) << "18.9 m is the first 0.9 m record under 30 px";
    EXPECT_EQ(plan.far_count, 3u);
    EXPECT_EQ(plan.distant_count, 3u);
    EXPECT_EQ(run_part(plan.runs[0], ImpostorPart::Near), std::make_pair(0u, 1u));
    EXPECT_EQ(run_part(plan.runs[0], ImpostorPart::Far), std::make_pair(1u, 3u));
    EXPECT_EQ(run_part(plan.runs[0], ImpostorPart::Distant), std::make_pair(3u, 5u));
    // The distant 1.8 m records stand 8 m to the right: their rectangle lies right of the screen's centre.
    EXPECT_GT(plan.distant_ndc_rect.x, 0.0f);
    EXPECT_LT(plan.ndc_rect.x, 0.0f) << "the far layer's records stand left of centre";

    in.distant_below_px = 0.0f;  // off: every far record at half resolution
    plan_far_layer(in, plan);
    EXPECT_EQ(plan.distant_count, 0u);
    EXPECT_EQ(plan.far_count, 6u);
    EXPECT_EQ(plan.runs[0].distant, plan.runs[0].end);
    in.distant_below_px = 70.0f;  // at the far limit: every far record in the distant layer
    plan_far_layer(in, plan);
    EXPECT_EQ(plan.far_count, 0u);
    EXPECT_EQ(plan.distant_count, 6u);
}

TEST(FarLayer, RectangleHoldsEveryFarQuadAndIsWholeScreenNearTheEye) {
    const View v;
    const std::vector<ImpostorAtlasLayout> layouts = {{16, 9, 1.0f, 0.0f, 1.8f}};
    Records r;
    for (int i = 0; i < 40; ++i) r.add(20.0f + 2.0f * float(i), -12.0f + 0.6f * float(i), 0);
    FarLayerPlan plan;
    plan_far_layer(input_of(v, r, layouts), plan);
    ASSERT_EQ(plan.far_count, 40u);
    // Every corner of every quad (width 1, height 1.8, facing the camera: here the xy plane), in NDC.
    for (const ImpostorInstance& rec : r.records)
        for (const float dx : {-0.5f, 0.5f})
            for (const float dy : {0.0f, 1.8f}) {
                const glm::vec4 c = v.clip * glm::vec4(glm::vec3(rec.position_scale) + glm::vec3(dx, dy, 0.0f), 1.0f);
                const glm::vec2 ndc = glm::vec2(c) / c.w;
                EXPECT_GE(ndc.x, plan.ndc_rect.x);
                EXPECT_LE(ndc.x, plan.ndc_rect.z);
                EXPECT_GE(ndc.y, plan.ndc_rect.y);
                EXPECT_LE(ndc.y, plan.ndc_rect.w);
            }
    EXPECT_LT(plan.ndc_rect.w - plan.ndc_rect.y, 1.0f) << "a band, not the whole screen: the quads lie along the horizon";

    Records near_eye;
    near_eye.add(30.0f, 0.0f, 0);
    near_eye.records[0].position_scale.w = 40.0f;  // a 72 m quad whose sphere reaches behind the eye (never under 70 px
    FarLayerInput in = input_of(v, near_eye, layouts);  // in practice; below_px raised so that it goes to the layer)
    in.below_px = 1e6f;
    plan_far_layer(in, plan);
    ASSERT_EQ(plan.far_count, 1u);
    EXPECT_EQ(plan.ndc_rect, glm::vec4(-1.0f, -1.0f, 1.0f, 1.0f));
}

// Meshes: in each group (nearest first) those under the mesh limit go last, nearest first (a tall one far away
// stays at full resolution); their spheres join the rectangle; 0 turns it off.
TEST(FarLayer, EachMeshGroupsMeshesUnderTheLimitGoLastAndTheRectangleHoldsThem) {
    const View v;
    Records none;
    // Group 0: five 1.7 m figures; under 120 px beyond 623.5 * 1.7 / 120 = 8.83 m. Group 1: two, the nearer 7 m tall.
    const std::vector<float> depth = {4.0f, 8.8f, 8.9f, 20.0f, 6.0f, 30.0f, 50.0f};
    std::vector<FarMeshBound> bounds;
    for (size_t i = 0; i < depth.size(); ++i) {
        const float x = -3.0f + float(i);
        bounds.push_back({glm::vec4(x, 0.0f, -depth[i], 0.9f), 1.7f});
    }
    bounds[5].height = 7.0f;  // 623.5 * 7 / 30 = 145 px at 30 m: kept at full resolution
    std::vector<uint32_t> order = {0, 1, 4, 2, 3, 5, 6};  // group 0 = [0, 5) nearest first, group 1 = [5, 7)
    std::sort(order.begin(), order.begin() + 5, [&](uint32_t a, uint32_t b) { return depth[a] < depth[b]; });
    const std::vector<FarMeshGroup> groups = {{0, 5}, {5, 2}};
    FarLayerInput in = input_of(v, none, {});
    in.mesh_order = order;
    in.mesh_groups = groups;
    in.mesh_bounds = bounds;
    in.mesh_depth = depth;
    in.meshes_below_px = 120.0f;
    FarLayerPlan plan;
    plan_far_layer(in, plan);
    ASSERT_EQ(plan.mesh_splits.size(), 2u);
    EXPECT_EQ(plan.mesh_splits[0], 3u) << "4, 6 and 8.8 m are at least 120 px; 8.9 and 20 m are under";
    EXPECT_EQ(std::vector<uint32_t>(order.begin(), order.begin() + 5), (std::vector<uint32_t>{0, 4, 1, 2, 3}));
    EXPECT_EQ(plan.mesh_splits[1], 6u) << "the 7 m mesh at 30 m stays; 50 m goes";
    EXPECT_EQ(plan.far_meshes, 3u);
    EXPECT_EQ(plan.far_count, 3u);
    for (uint32_t k : {3u, 4u, 6u}) {  // each far sphere's extreme points lie inside the rectangle
        const glm::vec4 s = bounds[order[k]].sphere;
        for (const glm::vec3 d : {glm::vec3(1, 0, 0), glm::vec3(-1, 0, 0), glm::vec3(0, 1, 0), glm::vec3(0, -1, 0)}) {
            const glm::vec4 c = v.clip * glm::vec4(glm::vec3(s) + s.w * d, 1.0f);
            const glm::vec2 ndc = glm::vec2(c) / c.w;
            EXPECT_GE(ndc.x, plan.ndc_rect.x);
            EXPECT_LE(ndc.x, plan.ndc_rect.z);
            EXPECT_GE(ndc.y, plan.ndc_rect.y);
            EXPECT_LE(ndc.y, plan.ndc_rect.w);
        }
    }

    in.meshes_below_px = 0.0f;  // off
    plan_far_layer(in, plan);
    EXPECT_EQ(plan.far_count, 0u);
    EXPECT_EQ(plan.mesh_splits[0], 5u);
    EXPECT_EQ(plan.mesh_splits[1], 7u);
}

}  // namespace
}  // namespace aloha
