// impostor_share_between (systems/frame/impostor_share.hpp): a scaled copy shares, a surface moved by more than the
// tolerance or coloured otherwise does not, and inputs that differ in anything else are not compared. Bounds come
// from the geometry of the cases (a vertex moved by d lies within d of the surface it left: its old place is on it).
#include "systems/frame/impostor_share.hpp"
#include "tests/common/lopsided_figure.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace aloha {
namespace {

// The lopsided figure (1.77 m tall) with texture coordinates whose u picks one of four columns by height (feet,
// legs, body, head) and v follows the height.
struct Figure : test::LopsidedFigure {
    std::vector<glm::vec2> uvs;
    Figure() {
        for (const glm::vec3& p : positions) {
            const float column = p.y < 0.1f ? 0.0f : p.y < 0.8f ? 1.0f : p.y < 1.43f ? 2.0f : 3.0f;
            uvs.emplace_back((column + 0.5f) / 4.0f, 1.0f - p.y / 1.8f);
        }
    }
};

// Four columns of one colour each: dark red, green, blue, light grey (sRGB bytes).
TextureImage columns_texture() {
    TextureImage t;
    t.name = "columns";
    t.width = 4;
    t.height = 1;
    t.rgba = {120, 20, 20, 255, 30, 140, 40, 255, 20, 40, 150, 255, 200, 200, 200, 255};
    return t;
}

struct Inputs {
    Figure fig;
    std::vector<SurfaceMaterial> materials{SurfaceMaterial{.name = "cloth", .texture = 0}};
    std::vector<TextureImage> textures{columns_texture()};
    std::vector<uint16_t> vertex_material;
    Inputs() { vertex_material.assign(fig.positions.size(), 0); }
    // The figure with its positions mapped by `move` in every one of `rows` rows.
    template <class Move>
    ImpostorBakeInput input(size_t rows, Move move, std::span<const glm::vec2> uvs = {}) const {
        ImpostorBakeInput in;
        in.name = "figure";
        in.indices = fig.indices;
        in.uvs = uvs.empty() ? std::span<const glm::vec2>(fig.uvs) : uvs;
        in.vertex_material = vertex_material;
        in.materials = materials;
        in.textures = textures;
        in.cull_back_faces = true;
        ImpostorPose pose{fig.positions, fig.normals};
        for (glm::vec3& p : pose.positions) p = move(p);
        in.rows.assign(rows, pose);
        return in;
    }
};

const auto same = [](glm::vec3 p) { return p; };

TEST(ImpostorShare, AScaledCopySharesAtItsScale) {
    const Inputs f;
    const ImpostorBakeInput owner = f.input(3, same);
    const ImpostorBakeInput taller = f.input(3, [](glm::vec3 p) { return p * 1.25f; });
    const ImpostorShare s = impostor_share_between(owner, taller);
    ASSERT_TRUE(s.comparable);
    EXPECT_NEAR(s.scale, 1.25f, 1e-5f);
    EXPECT_LT(s.distance_px, 1e-3f) << "the same surface to float rounding";
    EXPECT_LT(s.colour_steps, 1e-3f);
    EXPECT_TRUE(s.shareable(kImpostorShareTolerancePx, kImpostorShareToleranceSteps));
    // And the other way: the taller one's atlas drawn 0.8 times as large.
    const ImpostorShare back = impostor_share_between(taller, owner);
    EXPECT_NEAR(back.scale, 0.8f, 1e-5f);
    EXPECT_LT(back.distance_px, 1e-3f);
}

// The head moved forward by `d` atlas pixels (impostor_texel_size of the owner): every moved vertex lies within d of
// the surface it left (its old place is on it) and the head's foremost vertex, moved along the axis through the
// sphere's front, lies about d from it; so the distance found is at most d and, for d of a few pixels, near it.
TEST(ImpostorShare, ASurfaceMovedByMoreThanTheTolerancePixelsDoesNotShare) {
    const Inputs f;
    const ImpostorBakeInput owner = f.input(2, same);
    const float texel = impostor_texel_size(owner);
    EXPECT_NEAR(texel, 1.77f * 1.08f / 96.0f, 1e-5f) << "the cell: the figure's 1.77 m and 4% margins each side over 96 px";
    for (const float d : {0.4f, 2.5f}) {
        SCOPED_TRACE("moved " + std::to_string(d) + " px");
        const auto move_head = [&](glm::vec3 p) { return p.y > 1.43f ? p + glm::vec3(0.0f, 0.0f, d * texel) : p; };
        ImpostorBakeInput moved = f.input(2, move_head);
        moved.rows[0] = owner.rows[0];  // only the second row moves: every row is compared
        const ImpostorShare s = impostor_share_between(owner, moved);
        ASSERT_TRUE(s.comparable);
        EXPECT_NEAR(s.scale, 1.0f, 1e-6f) << "the head moves forward, not up";
        EXPECT_LE(s.distance_px, d * 1.0001f);
        if (d < kImpostorShareTolerancePx) {
            EXPECT_TRUE(s.shareable(kImpostorShareTolerancePx, kImpostorShareToleranceSteps)) << s.distance_px;
        } else {
            EXPECT_GT(s.distance_px, kImpostorShareTolerancePx) << "stopped at the first vertex over the tolerance";
            EXPECT_FALSE(s.shareable(kImpostorShareTolerancePx, kImpostorShareToleranceSteps));
        }
    }
}

// Texture coordinates moved by one column (every region showing its neighbour's colour) on the same surface: the
// albedo differs at every vertex by the columns' difference (up to 130 steps in a channel, LINEAR), far over the
// tolerance; the same coordinates differ by nothing.
TEST(ImpostorShare, AnotherTextureLayoutOnTheSameSurfaceDoesNotShare) {
    const Inputs f;
    std::vector<glm::vec2> shifted = f.fig.uvs;
    for (glm::vec2& uv : shifted) uv.x = std::fmod(uv.x + 0.25f, 1.0f);
    const ImpostorBakeInput owner = f.input(2, same), other = f.input(2, same, shifted);
    const ImpostorShare s = impostor_share_between(owner, other);
    ASSERT_TRUE(s.comparable);
    EXPECT_LT(s.distance_px, 1e-3f);
    EXPECT_GT(s.colour_steps, 4.0f * kImpostorShareToleranceSteps) << "measured: " << s.colour_steps;
    EXPECT_FALSE(s.shareable(kImpostorShareTolerancePx, kImpostorShareToleranceSteps));
    std::printf("[ measured ] texture coordinates one column apart: %.2f steps on average\n", s.colour_steps);
}

TEST(ImpostorShare, InputsThatDifferInMoreThanTheSurfaceAreNotCompared) {
    const Inputs f;
    const ImpostorBakeInput owner = f.input(2, same);
    auto expect_not_comparable = [&](const ImpostorBakeInput& other, const char* what) {
        const ImpostorShare s = impostor_share_between(owner, other);
        EXPECT_FALSE(s.comparable) << what;
        EXPECT_TRUE(std::isinf(s.distance_px)) << what;
        EXPECT_FALSE(s.shareable(kImpostorShareTolerancePx, kImpostorShareToleranceSteps)) << what;
    };
    expect_not_comparable(f.input(3, same), "another number of rows");
    ImpostorBakeInput views = f.input(2, same);
    views.directions = 8;
    expect_not_comparable(views, "other directions");
    ImpostorBakeInput bands = f.input(2, same);
    bands.elevations = 3;
    expect_not_comparable(bands, "other bands");
    ImpostorBakeInput culled = f.input(2, same);
    culled.cull_back_faces = false;
    expect_not_comparable(culled, "back faces drawn");
    const std::vector<SurfaceMaterial> red{SurfaceMaterial{.name = "cloth", .base_colour = {1.0f, 0.0f, 0.0f, 1.0f}, .texture = 0}};
    ImpostorBakeInput material = f.input(2, same);
    material.materials = red;
    expect_not_comparable(material, "another material");
    std::vector<TextureImage> other_texture{columns_texture()};
    other_texture[0].rgba[0] = 0;
    ImpostorBakeInput texture = f.input(2, same);
    texture.textures = other_texture;
    expect_not_comparable(texture, "another texture");
    const std::vector<glm::vec4> colours(f.fig.positions.size(), glm::vec4(1.0f));
    ImpostorBakeInput coloured = f.input(2, same);
    coloured.colours = colours;
    expect_not_comparable(coloured, "vertex colours on one side only");
    const std::vector<glm::vec2> too_few(f.fig.uvs.begin(), f.fig.uvs.end() - 1);
    expect_not_comparable(f.input(2, same, too_few), "texture coordinates that do not fit the vertices");
}

}  // namespace
}  // namespace aloha
