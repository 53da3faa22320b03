// The generated body look on the built-in humanoid: bone regions found from the skeleton's shape, grid
// UVs in the right texture column per muscle, UVs at every mesh level (subdivided through the
// stencils), and the generated texture's columns.
#include "systems/geometry/controller/body_texture.hpp"
#include "systems/geometry/controller/geometry_controller.hpp"
#include "test_humanoid.hpp"

#include <gtest/gtest.h>

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
    const std::vector<glm::vec2> uv = body_skin_uvs(g->skeleton(), g->rest_model(), g->muscles(), skin.rest_positions, skin.dominant_muscle);
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
    EXPECT_LT(px(224, 255).r, 20);                  // shoe sole: near black
}

}  // namespace
}  // namespace aloha
