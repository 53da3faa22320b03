// glTF metallic-roughness in the CrowdRenderer on lavapipe under validation (shaders/pbr.glsl). The square
// [-1, 1]^2 (normal +z) is seen from a camera at (0, 0, 3), so the direction to the camera, and with it the
// specular term, changes across the image.
// - Every pixel against the glTF specification's BRDF (Appendix B: Schlick Fresnel, GGX distribution,
//   height-correlated Smith visibility, alpha = roughness^2) and Karis's environment fit, evaluated here in double
//   precision at the pixel centre's point of the square, per pixel; per vertex, the same evaluated at the corners
//   and interpolated across each triangle, with the factors at the 8 bits the shader reads them. Tolerance 1 LSB:
//   the output's rounding to 8 bits plus float error.
// - Checks that do not share those formulas: a white metal of roughness 0 under an even white sky is white (the
//   fit's E = 1 for F0 = 1 at roughness 0: the furnace test); a smooth metal's brightest pixel lies where the key
//   light's mirror direction meets the camera; a map's green and blue channels give what the same factors give.
#include "material_square.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace aloha {
namespace {

using namespace material_test;
using MetallicRoughnessRender = MaterialRenderFixture;

struct Lights {
    glm::dvec3 l, key, sky, ground;
    double ambient = 0.0;
};

double unit_clamp(double v) { return std::clamp(v, 0.0, 1.0); }

// The light towards the camera from the square's point p (z = 0, normal +z), written from the glTF specification.
glm::dvec3 reference(glm::dvec3 base, double metallic, double roughness, glm::dvec3 p, const Lights& li) {
    const double pi = 3.14159265358979;
    const glm::dvec3 n(0, 0, 1), v = glm::normalize(glm::dvec3(0, 0, kCameraZ) - p), l = glm::normalize(li.l);
    const double r = std::clamp(roughness, 0.0, 1.0), a = r * r, rk = std::max(r, 0.045), a2 = std::pow(rk, 4.0);
    const glm::dvec3 c_diff = base * (1.0 - metallic), f0 = glm::mix(glm::dvec3(0.04), base, metallic);
    const double nv = std::clamp(glm::dot(n, v), 1e-4, 1.0), nl = std::max(glm::dot(n, l), 0.0);
    glm::dvec3 key(0.0);
    if (nl > 0.0) {
        const glm::dvec3 h = glm::normalize(l + v);
        const double nh = std::max(glm::dot(n, h), 0.0), vh = std::max(glm::dot(v, h), 0.0);
        const glm::dvec3 f = f0 + (1.0 - f0) * std::pow(1.0 - vh, 5.0);
        const double d = a2 / (pi * std::pow(nh * nh * (a2 - 1.0) + 1.0, 2.0));
        const double vis = 0.5 / (nl * std::sqrt(nv * nv * (1.0 - a2) + a2) + nv * std::sqrt(nl * nl * (1.0 - a2) + a2));
        key = ((1.0 - f) * c_diff + pi * d * vis * f) * nl;
    }
    // Karis, "Physically Based Shading on Mobile": E = f0 A + B.
    const glm::dvec4 k = r * glm::dvec4(-1.0, -0.0275, -0.572, 0.022) + glm::dvec4(1.0, 0.0425, 1.04, -0.04);
    const double a004 = std::min(k.x * k.x, std::exp2(-9.28 * nv)) * k.x + k.y;
    const glm::dvec3 e = f0 * (-1.04 * a004 + k.z) + (1.04 * a004 + k.w);
    const glm::dvec3 mirror = glm::reflect(-v, n);
    const glm::dvec3 hemi_n = glm::mix(li.ground, li.sky, 0.5 + 0.5 * n.y), hemi_r = glm::mix(li.ground, li.sky, 0.5 + 0.5 * mirror.y);
    const glm::dvec3 ambient = c_diff * (1.0 - e) * hemi_n + e * glm::mix(hemi_r, hemi_n, a);
    return li.ambient * ambient + (1.0 - li.ambient) * li.key * key;
}

// The square's point at pixel (col, row)'s centre (row 0 at the top, y = 1).
glm::dvec3 point_of(uint32_t col, uint32_t row) {
    return {-1.0 + (col + 0.5) * 2.0 / kSize, 1.0 - (row + 0.5) * 2.0 / kSize, 0.0};
}

FrameInput frame_of(const Lights& li) {
    FrameInput f;
    f.light_direction = glm::vec3(li.l);
    f.ambient = static_cast<float>(li.ambient);
    f.key_colour = glm::vec3(li.key);
    f.sky_colour = glm::vec3(li.sky);
    f.ground_colour = glm::vec3(li.ground);
    return f;
}

// Largest |pixel - 255 want(col, row)| over the image, every colour channel.
template <class Want>
int worst_against(const gpu::Rgba8Image& img, Want&& want) {
    int out = 0;
    for (uint32_t row = 0; row < kSize; ++row)
        for (uint32_t col = 0; col < kSize; ++col) {
            const glm::dvec3 w = want(col, row);
            for (int c = 0; c < 3; ++c)
                out = std::max(out, static_cast<int>(std::lround(std::abs(img.pixels[(size_t{row} * kSize + col) * 4 + size_t(c)] - unit_clamp(w[c]) * 255.0))));
        }
    return out;
}

SurfaceMaterial pbr_material(glm::vec3 linear_base, float metallic, float roughness) {
    SurfaceMaterial m;
    m.base_colour = glm::vec4(linear_base, 1.0f);
    m.metallic_roughness = true;
    m.metallic = metallic;
    m.roughness = roughness;
    return m;
}

TEST_F(MetallicRoughnessRender, EveryPixelFollowsTheSpecificationsBrdf) {
    const glm::vec3 linear(0.8f, 0.4f, 0.2f);
    const glm::dvec3 base = glm::pow(glm::dvec3(linear), glm::dvec3(1.0 / 2.2));  // drawn display-encoded, as base colours are
    const Lights lights[] = {
        {glm::normalize(glm::dvec3(0.2, -0.1, 1.0)), glm::dvec3(1.0), glm::dvec3(1.0), glm::dvec3(1.0), 0.0},
        {glm::normalize(glm::dvec3(-0.3, 0.6, 0.7)), glm::dvec3(1.0, 0.95, 0.9), glm::dvec3(0.6, 0.7, 1.0), glm::dvec3(0.4, 0.3, 0.2), 0.45},
    };
    const struct {
        float metallic, roughness;
    } surfaces[] = {{0.0f, 0.5f}, {1.0f, 0.3f}, {0.5f, 0.8f}, {1.0f, 0.0f}, {0.0f, 1.0f}};
    Square corners;
    for (const Lights& li : lights)
        for (const auto& s : surfaces) {
            const SurfaceMaterial m = pbr_material(linear, s.metallic, s.roughness);
            Result<gpu::Rgba8Image> img = draw_square(*renderer, *ctx, m, {}, corners, false, frame_of(li));
            ASSERT_TRUE(img.ok()) << img.error().to_string();
            // The factors reach the shader as a texel, 8 bits each.
            const double metallic = std::round(s.metallic * 255.0) / 255.0, roughness = std::round(s.roughness * 255.0) / 255.0;
            const int err = worst_against(img.value(), [&](uint32_t col, uint32_t row) { return reference(base, metallic, roughness, point_of(col, row), li); });
            EXPECT_LE(err, 1) << "per pixel, metallic " << s.metallic << ", roughness " << s.roughness << ", ambient " << li.ambient;
            // Per vertex: the corners' light, interpolated across the triangles (0, 1, 3) and (0, 3, 2), clamped after.
            Result<gpu::Rgba8Image> vimg = draw_square(*renderer, *ctx, m, {}, corners, true, frame_of(li));
            ASSERT_TRUE(vimg.ok()) << vimg.error().to_string();
            auto at = [&](double x, double y) { return reference(base, metallic, roughness, glm::dvec3(x, y, 0.0), li); };
            const int verr = worst_against(vimg.value(), [&](uint32_t col, uint32_t row) {
                const glm::dvec3 p = point_of(col, row);
                const double u = (p.x + 1.0) / 2.0, w = (p.y + 1.0) / 2.0;  // 0..1 from the corner (-1, -1)
                return p.y <= p.x ? (1.0 - u) * at(-1, -1) + (u - w) * at(1, -1) + w * at(1, 1)
                                  : (1.0 - w) * at(-1, -1) + u * at(1, 1) + (w - u) * at(-1, 1);
            });
            EXPECT_LE(verr, 1) << "per vertex, metallic " << s.metallic << ", roughness " << s.roughness << ", ambient " << li.ambient;
        }
}

TEST_F(MetallicRoughnessRender, WhiteMirrorMetalUnderAnEvenWhiteSkyIsWhite) {
    const SurfaceMaterial m = pbr_material(glm::vec3(1.0f), 1.0f, 0.0f);
    Square corners;
    for (const bool vertex_lit : {false, true}) {
        Result<gpu::Rgba8Image> img = draw_square(*renderer, *ctx, m, {}, corners, vertex_lit, ambient_only());
        ASSERT_TRUE(img.ok()) << img.error().to_string();
        EXPECT_LE(worst(img.value(), glm::vec3(1.0f)), 1) << (vertex_lit ? "per vertex" : "per pixel");
    }
}

TEST_F(MetallicRoughnessRender, SmoothMetalsHighlightIsWhereTheKeyLightsMirrorMeetsTheCamera) {
    const SurfaceMaterial m = pbr_material(glm::vec3(1.0f), 1.0f, 0.15f);
    const glm::vec3 light = glm::normalize(glm::vec3(0.15f, -0.1f, 1.0f));
    Square corners;
    Result<gpu::Rgba8Image> img = draw_square(*renderer, *ctx, m, {}, corners, false, key_only(light));
    ASSERT_TRUE(img.ok()) << img.error().to_string();
    // The mirror point: the camera sees the light's reflection where (camera - p) is parallel to the mirror of the
    // light, (-lx, -ly, lz): p = kCameraZ (lx, ly) / lz.
    const double x = kCameraZ * light.x / light.z, y = kCameraZ * light.y / light.z;
    // The lobe may clip at 255 over a few pixels: its centre is the centroid of the pixels within 90% of the peak.
    double sum = 0.0, cx = 0.0, cy = 0.0;
    int peak = 0;
    for (size_t i = 0; i < size_t{kSize} * kSize; ++i) peak = std::max(peak, int(img.value().pixels[i * 4 + 1]));
    ASSERT_GT(peak, 200) << "a white smooth metal shows the key light";
    for (uint32_t row = 0; row < kSize; ++row)
        for (uint32_t col = 0; col < kSize; ++col) {
            const int g = img.value().pixels[(size_t{row} * kSize + col) * 4 + 1];
            if (g < 0.9 * peak) continue;
            const glm::dvec3 p = point_of(col, row);
            sum += g;
            cx += g * p.x;
            cy += g * p.y;
        }
    const double pixel = 2.0 / kSize;
    EXPECT_NEAR(cx / sum, x, pixel) << "in world units; one pixel is " << pixel;
    EXPECT_NEAR(cy / sum, y, pixel);
}

TEST_F(MetallicRoughnessRender, MapsGreenIsRoughnessAndBlueIsMetalness) {
    Square sq;
    sq.uvs = {{0, 1}, {1, 1}, {0, 0}, {1, 0}};
    const uint32_t ids[1] = {renderer->register_texture(one_texel({0, 77, 255, 255}, "metallic-roughness")).value()};
    SurfaceMaterial mapped = pbr_material(glm::vec3(0.9f, 0.6f, 0.3f), 1.0f, 1.0f);
    mapped.metallic_roughness_texture = 0;
    const SurfaceMaterial factors = pbr_material(glm::vec3(0.9f, 0.6f, 0.3f), 1.0f, 77.0f / 255.0f);
    const FrameInput light = key_only(glm::normalize(glm::vec3(0.1f, 0.2f, 1.0f)));
    for (const bool vertex_lit : {false, true}) {
        Result<gpu::Rgba8Image> a = draw_square(*renderer, *ctx, mapped, ids, sq, vertex_lit, light);
        Result<gpu::Rgba8Image> b = draw_square(*renderer, *ctx, factors, {}, sq, vertex_lit, light);
        ASSERT_TRUE(a.ok() && b.ok());
        int diff = 0;
        for (size_t i = 0; i < a.value().pixels.size(); ++i) diff = std::max(diff, std::abs(int(a.value().pixels[i]) - int(b.value().pixels[i])));
        EXPECT_EQ(diff, 0) << (vertex_lit ? "per vertex" : "per pixel");
    }
    SurfaceMaterial bad = factors;
    bad.metallic = 1.5f;
    EXPECT_FALSE(renderer->register_material(bad).ok()) << "metalness out of [0, 1]";
}

}  // namespace
}  // namespace aloha
