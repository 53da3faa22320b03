// The generated body look on the built-in humanoid: bone regions found from the skeleton's shape, grid
// UVs in the right texture column per muscle, UVs at every mesh level (subdivided through the
// stencils), and the generated texture's columns.
#include "systems/geometry/controller/body_texture.hpp"
#include "systems/geometry/controller/geometry_controller.hpp"
#include "test_humanoid.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>

namespace aloha {
namespace {

TEST(BodyTexture, HumanoidRegionsFromTheSkeletonShape) {
    const CharacterGeometry* g = test::humanoid().geometry.get();
    ASSERT_TRUE(g);
    const Skeleton& s = g->skeleton();
    const std::vector<BodyRegion> r = bone_regions(s, g->rest_model());
    auto region = [&](const char* joint) {
        const int j = s.find(joint);
        EXPECT_GE(j, 0) << joint;
        return j >= 0 ? r[static_cast<size_t>(j)] : BodyRegion::Shirt;
    };
    EXPECT_EQ(region("Head"), BodyRegion::Skin);
    EXPECT_EQ(region("Chest"), BodyRegion::Shirt);
    EXPECT_EQ(region("LeftShoulder"), BodyRegion::Shirt);   // upper arm: sleeve
    EXPECT_EQ(region("RightShoulder"), BodyRegion::Shirt);
    EXPECT_EQ(region("LeftElbow"), BodyRegion::Skin);       // forearm
    EXPECT_EQ(region("RightWrist"), BodyRegion::Skin);      // hand
    EXPECT_EQ(region("LeftHip"), BodyRegion::Trousers);     // thigh
    EXPECT_EQ(region("RightKnee"), BodyRegion::Trousers);   // shin
    EXPECT_EQ(region("LeftAnkle"), BodyRegion::Shoes);      // foot
}

TEST(BodyTexture, SkinVerticesTakeTheirDominantMusclesColumn) {
    const CharacterGeometry* g = test::humanoid().geometry.get();
    ASSERT_TRUE(g);
    const SkinLayer& skin = g->skin_layer(8, 6);
    // Without the hems' smoothing (no triangles), every vertex is at the centre of its dominant muscle's column.
    const std::vector<glm::vec2> uv = body_skin_uvs(g->skeleton(), g->rest_model(), g->muscles(), skin.rest_positions, skin.dominant_muscle, {});
    ASSERT_EQ(uv.size(), skin.rest_positions.size());
    // The column of the vertices whose dominant muscle is `muscle` (all equal), or -1 when none.
    auto column = [&](const char* muscle) {
        const int m = g->muscles().find(muscle);
        EXPECT_GE(m, 0) << muscle;
        float u = -1.0f;
        for (size_t i = 0; i < uv.size(); ++i) {
            if (static_cast<int>(skin.dominant_muscle[i]) != m) continue;
            if (u >= 0.0f) {
                EXPECT_EQ(uv[i].x, u) << muscle;
            }
            u = uv[i].x;
        }
        return u;
    };
    EXPECT_FLOAT_EQ(column("head"), 0.125f);
    EXPECT_FLOAT_EQ(column("hand_l"), 0.125f);
    EXPECT_FLOAT_EQ(column("soleus_l"), 0.625f);
    EXPECT_FLOAT_EQ(column("biceps_r"), 0.375f);
    EXPECT_FLOAT_EQ(column("vastus_lateralis_l"), 0.625f);
    EXPECT_FLOAT_EQ(column("foot_r"), 0.875f);
    for (const glm::vec2& t : uv) {
        EXPECT_GE(t.y, 0.0f);
        EXPECT_LE(t.y, 1.0f);
    }
    // v spans the skin's own height: 0 at the top of the head, 1 at the soles (the texture's sole rows).
    const auto [lowest, highest] = std::minmax_element(skin.rest_positions.begin(), skin.rest_positions.end(),
                                                       [](const glm::vec3& a, const glm::vec3& b) { return a.y < b.y; });
    EXPECT_FLOAT_EQ(uv[static_cast<size_t>(highest - skin.rest_positions.begin())].y, 0.0f);
    EXPECT_FLOAT_EQ(uv[static_cast<size_t>(lowest - skin.rest_positions.begin())].y, 1.0f);
    // With them, each vertex stays within its own column or the half of a neighbouring column next to it, and v
    // is unchanged.
    const std::vector<glm::vec2> hemmed =
        body_skin_uvs(g->skeleton(), g->rest_model(), g->muscles(), skin.rest_positions, skin.dominant_muscle, skin.indices);
    for (size_t i = 0; i < uv.size(); ++i) {
        EXPECT_LE(std::abs(hemmed[i].x - uv[i].x), 0.25f + 1e-6f) << i;
        EXPECT_EQ(hemmed[i].y, uv[i].y);
    }
}

// The hem between `border`'s two columns near `joint` (segments with their middle within 15 cm at rest): in each
// triangle whose corners' u straddle the border, the segment between the two points where u crosses it (linear
// along the edges, as the rasteriser interpolates u). Its length, and how far it turns in all (the sum of the
// angles between consecutive segments, chained through the edge points they share).
struct HemLine {
    float length = 0.0f;
    float turning = 0.0f;
    size_t segments = 0;
};

HemLine hem_line(const SkinLayer& skin, const std::vector<glm::vec2>& uv, float border, glm::vec3 joint) {
    using Edge = std::pair<uint32_t, uint32_t>;
    auto crossing = [&](uint32_t i, uint32_t j) {
        const float ui = uv[i].x - border, uj = uv[j].x - border;
        return glm::mix(skin.rest_positions[i], skin.rest_positions[j], ui / (ui - uj));
    };
    std::map<Edge, std::vector<glm::vec3>> at_edge;  // per crossed edge: the direction of each segment leaving its point
    HemLine h;
    for (size_t t = 0; t + 2 < skin.indices.size(); t += 3) {
        std::vector<Edge> crossed;
        for (int k = 0; k < 3; ++k) {
            const uint32_t i = skin.indices[t + static_cast<size_t>(k)], j = skin.indices[t + static_cast<size_t>((k + 1) % 3)];
            if ((uv[i].x < border) != (uv[j].x < border)) crossed.push_back({std::min(i, j), std::max(i, j)});
        }
        if (crossed.size() != 2) continue;
        const glm::vec3 a = crossing(crossed[0].first, crossed[0].second), b = crossing(crossed[1].first, crossed[1].second);
        if (glm::length(0.5f * (a + b) - joint) > 0.15f || glm::length(b - a) < 1e-6f) continue;
        h.length += glm::length(b - a);
        ++h.segments;
        const glm::vec3 d = glm::normalize(b - a);
        at_edge[crossed[0]].push_back(d);
        at_edge[crossed[1]].push_back(-d);
    }
    for (const auto& [edge, dirs] : at_edge)
        if (dirs.size() == 2) h.turning += std::acos(std::clamp(-glm::dot(dirs[0], dirs[1]), -1.0f, 1.0f));  // 0 when straight on
    return h;
}

TEST(BodyTexture, HemsRunAlongSmoothLinesNotTheTrianglesEdges) {
    // A hem follows the edges between vertices of two regions when each vertex takes its region's column centre: a
    // zigzag of triangle edges, broken further where muscle territories interleave. Smoothing the regions' shares
    // over kHemBand draws it as a line across the triangles. Measured on the top level's skin near the left elbow
    // (sleeve), the neck (neckline) and the hips (waist): how far the hem turns in all, and its length (a zigzag
    // is longer than the line it follows). A ring round a limb turns 2 pi in its plane, more over the muscles' relief
    // and where a mesh's irregular triangles bend the line at their edges. Measured at kHemBand 0.05 m: 0.43-0.51 of
    // the zigzag's turning, 0.55-0.75 of its length; the bounds (0.6 and 0.8) are regression guards from those.
    const CharacterGeometry* g = test::humanoid().geometry.get();
    ASSERT_TRUE(g);
    const Skeleton& s = g->skeleton();
    const SkinLayer& skin = g->skin_layer(16, 12);
    auto at = [&](const char* joint) { return glm::vec3(g->rest_model()[static_cast<size_t>(s.find(joint))][3]); };
    const std::vector<glm::vec2> zigzag = body_skin_uvs(s, g->rest_model(), g->muscles(), skin.rest_positions, skin.dominant_muscle, {});
    const std::vector<glm::vec2> hemmed = body_skin_uvs(s, g->rest_model(), g->muscles(), skin.rest_positions, skin.dominant_muscle, skin.indices);
    struct Hem {
        const char* name;
        float border;  // u between the two columns
        glm::vec3 joint;
    };
    const Hem hems[] = {{"sleeve", 0.25f, at("LeftElbow")}, {"neckline", 0.25f, at("lowerneck")}, {"waist", 0.5f, 0.5f * (at("LeftHip") + at("RightHip"))}};
    for (const Hem& h : hems) {
        const HemLine before = hem_line(skin, zigzag, h.border, h.joint), after = hem_line(skin, hemmed, h.border, h.joint);
        ASSERT_GE(before.segments, 8u) << h.name;
        ASSERT_GE(after.segments, 8u) << h.name;
        std::printf("[figure] %s: along the edges %.0f mm long turning %.1f rad (%zu segments); hemmed %.0f mm turning %.1f rad (%zu)\n", h.name,
                    static_cast<double>(1000.0f * before.length), static_cast<double>(before.turning), before.segments,
                    static_cast<double>(1000.0f * after.length), static_cast<double>(after.turning), after.segments);
        EXPECT_LT(after.turning, 0.6f * before.turning) << h.name;
        EXPECT_LT(after.length, 0.8f * before.length) << h.name;
    }
}

TEST(BodyTexture, EveryMeshLevelHasUvs) {
    const CharacterGeometry* g = test::humanoid().geometry.get();
    ASSERT_TRUE(g);
    const std::vector<GeomLod> levels = test::test_levels();
    GeometryController c(*g, levels, 1);
    for (uint8_t l = 0; l < c.level_count(); ++l) {
        const size_t vertices = c.vertices_per_character(l);
        EXPECT_EQ(c.level_uvs(l).size(), vertices) << "level " << int(l);
        EXPECT_TRUE(c.level_vertex_materials(l).empty());
    }
}

TEST(BodyTexture, GeneratedTextureColumns) {
    const TextureImage t = make_body_texture();
    ASSERT_EQ(t.width, 256u);
    ASSERT_EQ(t.rgba.size(), 256u * 256u * 4u);
    auto px = [&](uint32_t x, uint32_t y) { return glm::ivec3(t.rgba[(y * 256 + x) * 4], t.rgba[(y * 256 + x) * 4 + 1], t.rgba[(y * 256 + x) * 4 + 2]); };
    EXPECT_GT(px(32, 10).r, px(32, 10).b);          // skin: warm
    EXPECT_EQ(px(96, 0), glm::ivec3(237, 237, 230)); // shirt: light stripe on rows 0-5
    EXPECT_EQ(px(96, 6), glm::ivec3(41, 92, 168));   // then blue
    EXPECT_GT(px(160, 100).b, px(160, 100).r);      // trousers: blue
    EXPECT_LT(px(224, 255).r, 20);                  // shoe sole: near black, the last 5 rows
    EXPECT_LT(px(224, 252).r, 20);
    EXPECT_GT(px(224, 250).r, 60);                  // above it the brown upper
}

}  // namespace
}  // namespace aloha
