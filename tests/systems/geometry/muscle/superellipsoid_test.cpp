// Super-ellipsoid maths: signed powers, volume formula against numerical integration, exact
// normals against surface tangents, and volume-preserving radii (eq. 4-8).
#include "systems/geometry/muscle/superellipsoid.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

namespace aloha {
namespace {

constexpr double kPi = std::numbers::pi;

TEST(SuperEllipsoid, SignedPowKeepsSign) {
    EXPECT_FLOAT_EQ(signed_pow(-0.25f, 0.5f), -0.5f);
    EXPECT_FLOAT_EQ(signed_pow(0.25f, 0.5f), 0.5f);
    EXPECT_EQ(signed_pow(0.0f, 0.3f), 0.0f);
    EXPECT_DOUBLE_EQ(signed_pow(-8.0, 1.0 / 3.0), -2.0);
}

TEST(SuperEllipsoid, VolumeFactorOfEllipsoidIsEq4) {
    // A = B = 1 is the ellipsoid: V = 4 pi / 3 rx ry rz (eq. 4). Only rounding in lgamma/exp (~1e-15).
    EXPECT_NEAR(superellipsoid_volume_factor(1.0, 1.0), 4.0 * kPi / 3.0, 1e-12);
    EXPECT_NEAR(superellipsoid_volume({0.1, 0.2, 0.3}, 1.0, 1.0), 4.0 * kPi / 3.0 * 0.006, 1e-14);
}

// Volume by 2-D midpoint quadrature over the first octant of the unit-radius shape, integrating the
// height z(x, y) = (1 - (x^(2/B) + y^(2/B))^(B/A))^(A/2) exactly in the third dimension.
double quadrature_volume(double a, double b, int n) {
    const double h = 1.0 / n;
    double sum = 0.0;
    for (int i = 0; i < n; ++i) {
        const double x = (i + 0.5) * h;
        const double px = std::pow(x, 2.0 / b);
        for (int j = 0; j < n; ++j) {
            const double y = (j + 0.5) * h;
            const double inner = std::pow(px + std::pow(y, 2.0 / b), b / a);
            if (inner < 1.0) sum += std::pow(1.0 - inner, a / 2.0);
        }
    }
    return 8.0 * sum * h * h;
}

TEST(SuperEllipsoid, GeneralVolumeMatchesNumericalIntegration) {
    // Quadrature error: the boundary cells (O(n) of n^2) are mis-weighted by at most one cell each and
    // the height has a square-root edge, so the relative error is O(1/n) ~ 1e-3 at n = 1200; the
    // closed form must agree to 3e-3. The brief's variant 2/3 A B Beta(A/2, A+1) Beta(B/2, B/2) is
    // 2/3 of this (8 pi / 9 for the unit sphere), so it would fail here by 33 %.
    const double cases[][2] = {{1.0, 1.0}, {0.5, 0.5}, {0.3, 1.0}, {1.0, 0.4}, {1.5, 1.2}, {0.7, 1.8}};
    for (const auto& c : cases) {
        const double numeric = quadrature_volume(c[0], c[1], 1200);
        const double closed = superellipsoid_volume_factor(c[0], c[1]);
        EXPECT_NEAR(closed / numeric, 1.0, 3e-3) << "A=" << c[0] << " B=" << c[1];
    }
}

TEST(SuperEllipsoid, PointsLieOnTheImplicitSurface) {
    // F = 1 on the surface; float points, so |F - 1| is a few float ulps scaled by 2/A (~1e-5).
    const glm::vec3 r(0.2f, 0.05f, 0.03f);
    for (const auto ab : {glm::vec2(1, 1), glm::vec2(0.5f, 0.8f), glm::vec2(1.6f, 0.3f)})
        for (float th = -3.0f; th < 3.1f; th += 0.37f)
            for (float ph = -1.5f; ph < 1.5f; ph += 0.29f) {
                const glm::vec3 p = superellipsoid_point(r, ab.x, ab.y, th, ph);
                EXPECT_NEAR(superellipsoid_implicit(glm::dvec3(p), glm::dvec3(r), ab.x, ab.y), 1.0, 2e-4);
            }
}

TEST(SuperEllipsoid, NormalIsPerpendicularToTangentsAndOutward) {
    // Tangents by central differences of eq. 1-3 in double (step 1e-5: truncation ~1e-10); the
    // analytic normal must be orthogonal to them up to float rounding of the normal (~1e-6 relative).
    const glm::dvec3 r(0.15, 0.06, 0.04);
    const double a = 0.7, b = 1.3, e = 1e-5;
    auto P = [&](double th, double ph) {
        const double ca = signed_pow(std::cos(ph), a), sa = signed_pow(std::sin(ph), a);
        return glm::dvec3(r.x * ca * signed_pow(std::cos(th), b), r.y * ca * signed_pow(std::sin(th), b), r.z * sa);
    };
    for (double th = -3.0; th < 3.1; th += 0.41)
        for (double ph = -1.4; ph < 1.45; ph += 0.33) {
            const glm::dvec3 n(superellipsoid_normal(glm::vec3(r), float(a), float(b), float(th), float(ph)));
            EXPECT_NEAR(glm::length(n), 1.0, 1e-6);
            const glm::dvec3 tt = glm::normalize(P(th + e, ph) - P(th - e, ph));
            const glm::dvec3 tp = glm::normalize(P(th, ph + e) - P(th, ph - e));
            EXPECT_NEAR(glm::dot(n, tt), 0.0, 2e-5) << th << " " << ph;
            EXPECT_NEAR(glm::dot(n, tp), 0.0, 2e-5) << th << " " << ph;
            // Euler: F is homogeneous of degree 2/A, so p . grad F = 2/A > 0: outward.
            EXPECT_GT(glm::dot(n, P(th, ph)), 0.0);
        }
}

TEST(SuperEllipsoid, VolumePreservingRadiiKeepVolumeAndRatio) {
    const float k = static_cast<float>(superellipsoid_volume_factor(0.8, 1.2));
    const float v = 2.5e-4f, p = 1.4f;
    for (float length = 0.05f; length < 0.6f; length += 0.05f) {
        const glm::vec3 rr = volume_preserving_radii(length, v, p, k);
        EXPECT_FLOAT_EQ(rr.x, 0.5f * length);
        EXPECT_NEAR(rr.y / rr.z, p, 1e-6);
        // Float rounding of three radii and one sqrt: ~4 ulp relative, far below 1e-5.
        EXPECT_NEAR(superellipsoid_volume(glm::dvec3(rr), 0.8, 1.2) / v, 1.0, 1e-5);
    }
}

}  // namespace
}  // namespace aloha
