// Helpers of the OcclusionJob tests: a crowd scene, a level camera, solid cores, and a ray test against
// the vertical cylinders the job's shapes model.
#pragma once

#include "systems/lod/occlusion.hpp"

#include <gtest/gtest.h>

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

namespace aloha::occlusion_test {

/// Characters (feet, height, radius), all visible unless changed, and the job's scratch grid.
struct Scene {
    std::vector<Transform> t;
    std::vector<Bounds> b;
    std::vector<LodAttributes> a;
    std::vector<GeomLod> g;  // empty: every character counts as drawn
    OcclusionGrid grid;
    void add(glm::vec3 feet, float height = 1.8f, float radius = 0.4f) {
        Transform x;
        x.position = feet;
        t.push_back(x);
        b.push_back({height, radius});
        LodAttributes v;
        v.visible = 1;
        a.push_back(v);
    }
    size_t run(const LodCamera& cam, const OcclusionParams& p = {}) {
        OcclusionJob job{t, b, g, cam, p, &grid, a};
        std::vector<std::string> errors;
        EXPECT_TRUE(job.Validate(&errors)) << (errors.empty() ? "" : errors.front());
        return job.Run();
    }
};

/// The eye 1 m up at z = 10, looking along -z; 60 degree lens, 1280 x 720.
inline LodCamera level_camera() {
    return make_lod_camera({0, 1, 10}, {0, 1, 0}, glm::radians(60.0f), {1280, 720}, 0.1f, 500.0f);
}

// Cores as big as the bounds (a full-height cylinder of the bounds' radius): an occluder is a solid
// cylinder, so which cases are hidden can be worked out by hand. The estimate's body shapes are the same
// solid cylinder (legs and torso halves of it, no head).
inline OcclusionParams solid_cores() {
    OcclusionParams p;
    p.torso_y0 = 0.0f;
    p.torso_y1 = 1.0f;
    p.torso_radius = 0.25f;  // fraction of the height: 1 m for the 4 m occluder below
    p.neck_radius = 0.0f;
    p.head_radius = 0.0f;
    p.body_legs = {0.0f, 0.5f, 0.25f};
    p.body_torso = {0.5f, 1.0f, 0.25f};
    p.body_head = {0.99f, 1.0f, 0.0f};
    return p;
}

// True when the segment from `eye` to `p` passes through the vertical cylinder (axis through `base`,
// y in [y0, y1] above it, radius r) before reaching p.
inline bool ray_hits_cylinder(glm::vec3 eye, glm::vec3 p, glm::vec3 base, float y0, float y1, float r) {
    const glm::vec3 d = p - eye;  // parameter t in [0, 1) reaches p at 1
    // Inside the infinite cylinder: |(eye + t d - base).xz| <= r, a quadratic in t.
    const glm::vec2 o(eye.x - base.x, eye.z - base.z), dv(d.x, d.z);
    const float qa = glm::dot(dv, dv), qb = 2.0f * glm::dot(o, dv), qc = glm::dot(o, o) - r * r;
    const float disc = qb * qb - 4.0f * qa * qc;
    if (qa <= 0.0f || disc < 0.0f) return false;
    float t0 = (-qb - std::sqrt(disc)) / (2.0f * qa), t1 = (-qb + std::sqrt(disc)) / (2.0f * qa);
    // Inside the slab base.y + [y0, y1].
    const float lo = base.y + y0, hi = base.y + y1;
    if (std::fabs(d.y) < 1e-9f) {
        if (eye.y < lo || eye.y > hi) return false;
    } else {
        float s0 = (lo - eye.y) / d.y, s1 = (hi - eye.y) / d.y;
        if (s0 > s1) std::swap(s0, s1);
        t0 = std::max(t0, s0);
        t1 = std::min(t1, s1);
    }
    return t0 <= t1 && t1 > 0.0f && t0 < 1.0f;
}

}  // namespace aloha::occlusion_test
