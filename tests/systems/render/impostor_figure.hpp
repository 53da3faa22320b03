// The impostor tests' figure and image comparison: a lopsided figure of known pose, the camera circling it, and
// the check that an impostor render matches a direct render within the tolerance the atlas resolution allows
// (the derivation is beside compare()).
#pragma once

#include "engine/gpu/context.hpp"
#include "render_scene.hpp"
#include "systems/render/crowd_renderer.hpp"
#include "systems/render/impostor_atlas.hpp"
#include "tests/common/lopsided_figure.hpp"

#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

namespace aloha::impostor_test {

inline constexpr uint32_t kSize = 128;
inline constexpr float kDistance = 25.0f;

// The lopsided figure (tests/common/lopsided_figure.hpp): its views differ.
using Figure = test::LopsidedFigure;

// The figure in `rows` rows, all the same pose, in 16 directions of 96 px cells (the atlas compare() is derived for).
inline ImpostorBakeInput bake_input(const Figure& fig, size_t rows) {
    ImpostorBakeInput in;
    in.name = "figure";
    in.indices = fig.indices;
    in.rows.assign(rows, ImpostorPose{fig.positions, fig.normals});
    in.cull_back_faces = true;
    in.directions = 16;
    in.cell_height_px = 96;
    return in;
}

struct Mask {
    std::vector<uint8_t> on;
    [[nodiscard]] bool at(int x, int y) const { return x >= 0 && y >= 0 && x < int(kSize) && y < int(kSize) && on[size_t(y) * kSize + size_t(x)]; }
    // True when a pixel within `r` (Chebyshev) of (x, y) is on.
    [[nodiscard]] bool near(int x, int y, int r) const {
        for (int dy = -r; dy <= r; ++dy)
            for (int dx = -r; dx <= r; ++dx)
                if (at(x + dx, y + dy)) return true;
        return false;
    }
    // True when every pixel within `r` of (x, y) is on.
    [[nodiscard]] bool inside(int x, int y, int r) const {
        for (int dy = -r; dy <= r; ++dy)
            for (int dx = -r; dx <= r; ++dx)
                if (!at(x + dx, y + dy)) return false;
        return true;
    }
};

inline Mask mask_of(const gpu::Rgba8Image& img) {  // clear colour is black: the figure is every lit pixel
    Mask m;
    m.on.resize(size_t{kSize} * kSize);
    for (size_t i = 0; i < m.on.size(); ++i) m.on[i] = img.pixels[i * 4] + img.pixels[i * 4 + 1] + img.pixels[i * 4 + 2] > 0;
    return m;
}

// The camera kDistance from the point `target_y` up the vertical axis (the figure's mid-height by default) at
// `azimuth` about it and `elevation` above the level, aimed at it.
inline FrameInput camera_frame(float azimuth, float elevation = 0.0f, float target_y = 0.9f) {
    FrameInput f;
    const glm::vec3 target(0.0f, target_y, 0.0f);
    const glm::vec3 eye = target + kDistance * glm::vec3(std::sin(azimuth) * std::cos(elevation), std::sin(elevation),
                                                         std::cos(azimuth) * std::cos(elevation));
    f.camera.view = glm::lookAt(eye, target, glm::vec3(0, 1, 0));
    f.camera.proj = glm::perspective(2.0f * std::atan(1.05f / kDistance), 1.0f, 1.0f, 100.0f);  // 2.1 m over 128 px
    f.clear_colour = {0, 0, 0, 1};
    set_character_lighting(f);
    return f;
}

inline Result<gpu::Rgba8Image> draw(CrowdRenderer& r, gpu::Context& ctx, const FrameInput& frame) {
    return test::draw_square(r, ctx, frame, kSize);
}

// A renderer with the figure's topology and its baked atlas registered, drawing the figure directly and as an impostor
// from the same camera.
struct Bench {
    std::unique_ptr<CrowdRenderer> renderer;
    uint32_t topology = 0, atlas = 0;
    glm::vec4 tint{0.85f, 0.65f, 0.5f, 1.0f};

    // Registers `fig` and `baked` with a new renderer on `ctx` made with `options`; false (with the test failed) when
    // that fails.
    bool make(gpu::Context& ctx, const Figure& fig, const ImpostorAtlas& baked, const RendererOptions& options = {}) {
        Result<std::unique_ptr<CrowdRenderer>> made = CrowdRenderer::create(ctx, options);
        EXPECT_TRUE(made.ok()) << (made.ok() ? "" : made.error().to_string());
        if (!made.ok()) return false;
        renderer = std::move(made).value();
        Result<uint32_t> t = renderer->register_topology(fig.indices, 0, true);
        Result<uint32_t> a = renderer->register_impostor_atlas(baked.image, baked.layout);
        EXPECT_TRUE(t.ok() && a.ok()) << (a.ok() ? "" : a.error().to_string());
        if (!t.ok() || !a.ok()) return false;
        topology = t.value();
        atlas = a.value();
        return true;
    }

    // The figure turned by `heading` about +Y drawn directly, and its impostor at walk `phase` (< 0: the standing
    // row), both from camera_frame(azimuth, elevation). Empty images (with the test failed) where a draw fails.
    std::pair<gpu::Rgba8Image, gpu::Rgba8Image> draw_both(gpu::Context& ctx, const Figure& fig, float heading, float azimuth,
                                                          float elevation = 0.0f, float phase = 0.0f) {
        FrameInput direct = camera_frame(azimuth, elevation);
        const std::vector<DeformableMesh> meshes = {
            {topology, fig.positions, fig.normals, glm::rotate(glm::mat4(1.0f), heading, glm::vec3(0, 1, 0)), tint}};
        direct.meshes = meshes;
        FrameInput quad = camera_frame(azimuth, elevation);
        ImpostorInstance inst;
        inst.forward_phase = glm::vec4(std::sin(heading), std::cos(heading), phase, 1.0f);  // local +Z in world (x, z)
        inst.colour = tint;
        inst.atlas = atlas;
        quad.impostors = std::span(&inst, 1);
        Result<gpu::Rgba8Image> a = draw(*renderer, ctx, direct), b = draw(*renderer, ctx, quad);
        EXPECT_TRUE(a.ok() && b.ok());
        if (!a.ok() || !b.ok()) return {};
        return {std::move(a).value(), std::move(b).value()};
    }
};

// Tolerance. The atlas cell is 96 px for the figure's 1.8 m plus 8% margin (0.0203 m per texel); on screen
// 128 px span 2.1 m (0.0164 m per pixel), so a texel covers 1.24 pixels. The alpha-tested, bilinearly
// filtered edge moves by at most half a texel (0.62 px) plus half a pixel of sample-centre rounding; the
// orthographic bake against the perspective view changes the scale by at most the figure's depth over the
// distance (0.3 m / 25 m = 1.2%, 0.8 px at the 64 px from the image centre to its top): under 2 px in all,
// so every pixel of either silhouette is within 2 px of the other. For the same reason each impostor pixel
// inside both silhouettes shows what the direct render shows within 2 px of it: its colour lies in the
// range of the direct pixels of its 5 x 5 neighbourhood, widened by what the atlas itself loses: the
// normal's 8-bit quantisation (1 level) and its bilinear interpolation over 1.24-pixel texels, at most the
// change of the light across one pixel of the sharpest-curved part (the head, radius 0.13 m: 0.016 m turns
// the normal by 0.13 rad, the key light, 0.55 of the light, by 0.07 = 18 levels): 20 levels, for 99% of the
// pixels. The rest lie on the head's outline over the body, where the filtered (and mipmapped) normal mixes
// two surfaces' normals up to 90 degrees apart: the light of a normal on the arc between them exceeds both
// ends' by at most 1 - cos 45 = 0.29 of the light range (75 levels), the bound for every pixel. The mean
// absolute difference against the same pixel (not its neighbourhood) is at most 6 levels: half of that
// 20-level bound where the surface curves most, far less over the flatter body, plus the 1-level quantisation.
// `other` against `reference` within `r` px: silhouette pixels of either more than r px from the other's
// silhouette, and for each pixel r px inside both, its largest channel excess over the reference's range
// within r px and the summed |difference| from the same pixel.
struct Comparison {
    size_t area = 0, outside = 0;
    double sum = 0.0;
    std::vector<int> excess;  // per compared pixel
    [[nodiscard]] double mean() const { return excess.empty() ? 0.0 : sum / double(3 * excess.size()); }
};
inline Comparison compare(const gpu::Rgba8Image& reference, const gpu::Rgba8Image& other, int r) {
    const Mask a = mask_of(reference), b = mask_of(other);
    Comparison out;
    for (int y = 0; y < int(kSize); ++y)
        for (int x = 0; x < int(kSize); ++x) {
            out.area += a.at(x, y);
            if ((a.at(x, y) && !b.near(x, y, r)) || (b.at(x, y) && !a.near(x, y, r))) ++out.outside;
            if (!a.inside(x, y, r) || !b.inside(x, y, r)) continue;
            const size_t i = (size_t(y) * kSize + size_t(x)) * 4;
            int pixel_excess = 0;
            for (size_t c = 0; c < 3; ++c) {
                out.sum += std::abs(int(reference.pixels[i + c]) - int(other.pixels[i + c]));
                int lo = 255, hi = 0;  // the reference's range within r px
                for (int dy = -r; dy <= r; ++dy)
                    for (int dx = -r; dx <= r; ++dx) {
                        const int v = reference.pixels[(size_t(y + dy) * kSize + size_t(x + dx)) * 4 + c];
                        lo = std::min(lo, v);
                        hi = std::max(hi, v);
                    }
                const int v = other.pixels[i + c];
                pixel_excess = std::max(pixel_excess, v < lo ? lo - v : v > hi ? v - hi : 0);
            }
            out.excess.push_back(pixel_excess);
        }
    return out;
}

// The bounds derived above, with silhouettes and neighbourhoods `reach` px wide (2 for the level views), for a figure
// of more than `min_area` pixels.
inline void expect_matches(const gpu::Rgba8Image& direct, const gpu::Rgba8Image& impostor, int reach = 2, size_t min_area = 1500) {
    Comparison cmp = compare(direct, impostor, reach);
    const size_t area = cmp.area, outside = cmp.outside, compared = cmp.excess.size();
    std::vector<int>& excess = cmp.excess;
    const int worst = excess.empty() ? 0 : *std::max_element(excess.begin(), excess.end());
    const double sum = cmp.sum;
    EXPECT_GT(area, min_area) << "the level figure fills about 110 x 30 pixels";
    EXPECT_EQ(outside, 0u) << "silhouette pixels more than " << reach << " px from the other render's silhouette";
    ASSERT_GT(compared, min_area / 3) << "pixels at least `reach` px inside both silhouettes";
    EXPECT_LE(sum / double(3 * compared), 6.0) << "mean colour difference inside both silhouettes (levels)";
    std::sort(excess.begin(), excess.end());
    EXPECT_LE(excess[excess.size() * 99 / 100], 20) << "99th percentile of the colour difference from the direct render within " << reach << " px (levels)";
    EXPECT_LE(worst, 75) << "largest colour difference inside both silhouettes from the direct render within " << reach << " px (levels)";
}

}  // namespace aloha::impostor_test
