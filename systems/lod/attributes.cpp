#include "systems/lod/attributes.hpp"

#include "engine/core/look_at.hpp"

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cmath>

namespace aloha {

LodCamera make_lod_camera(glm::vec3 eye, glm::vec3 target, float fovy_rad, glm::vec2 viewport_px,
                          float near_plane, float far_plane) {
    LodCamera c;
    c.position = eye;
    c.view = look_at_y_up(eye, target);
    c.projection = glm::perspective(fovy_rad, viewport_px.x / viewport_px.y, near_plane, far_plane);
    c.viewport_px = viewport_px;
    c.near_plane = near_plane;
    c.far_plane = far_plane;
    return c;
}

bool LodAttributesJob::Validate(std::vector<std::string>* errors) const {
    bool ok = true;
    auto fail = [&](std::string m) {
        ok = false;
        if (errors) errors->push_back("LodAttributesJob: " + std::move(m));
    };
    const size_t n = transforms.size();
    if (output.size() != n) fail("output has " + std::to_string(output.size()) + " entries, expected " + std::to_string(n));
    if (!velocities.empty() && velocities.size() != n) fail("velocities size differs from transforms (and is not empty)");
    if (!bounds.empty() && bounds.size() != n) fail("bounds size differs from transforms (and is not empty)");
    if (!importance.empty() && importance.size() != n) fail("importance size differs from transforms (and is not empty)");
    if (!(camera.viewport_px.x > 0.0f && camera.viewport_px.y > 0.0f)) fail("camera viewport must be > 0 pixels");
    if (!(camera.near_plane > 0.0f && camera.far_plane > camera.near_plane)) fail("camera needs 0 < near < far");
    if (!(camera.projection[1][1] != 0.0f && std::isfinite(camera.projection[1][1])))
        fail("camera projection has no finite vertical scale (P[1][1])");
    return ok;
}

namespace {

// A plane n.x + d >= 0 is the inside; n has unit length.
glm::vec4 normalised(glm::vec4 p) { return p / glm::length(glm::vec3(p)); }

glm::vec4 row(const glm::mat4& m, int r) { return {m[0][r], m[1][r], m[2][r], m[3][r]}; }

}  // namespace

void LodAttributesJob::Run() const {
    const glm::mat4 vp = camera.projection * camera.view;
    const glm::vec4 r0 = row(vp, 0);
    const glm::vec4 r1 = row(vp, 1);
    const glm::vec4 r3 = row(vp, 3);
    const glm::vec4 depth_row = -row(camera.view, 2);  // view-space depth z = depth_row . (p, 1)
    // Side planes from the clip-space inequalities -w <= x, y <= w; near/far from the view depth.
    const glm::vec4 planes[6] = {
        normalised(r3 + r0),
        normalised(r3 - r0),
        normalised(r3 + r1),
        normalised(r3 - r1),
        normalised(depth_row - glm::vec4(0.0f, 0.0f, 0.0f, camera.near_plane)),
        normalised(-depth_row + glm::vec4(0.0f, 0.0f, 0.0f, camera.far_plane)),
    };
    float plane_xz[6];
    for (int k = 0; k < 6; ++k) plane_xz[k] = std::sqrt(planes[k].x * planes[k].x + planes[k].z * planes[k].z);
    const bool perspective = camera.projection[2][3] != 0.0f;
    const float height_scale = camera.projection[1][1] * camera.viewport_px.y * 0.5f;
    const Bounds default_bounds{};
    const Importance default_importance{};

    for (size_t i = 0; i < transforms.size(); ++i) {
        const Transform& t = transforms[i];
        const Bounds& b = bounds.empty() ? default_bounds : bounds[i];
        const float h = b.height * t.scale;
        const float half_h = 0.5f * h;
        const float radius = b.radius * t.scale;
        const glm::vec3 c = t.position + glm::vec3(0.0f, half_h, 0.0f);
        const glm::vec4 c4(c, 1.0f);
        LodAttributes& out = output[i];

        out.distance = glm::length(c - camera.position);
        const float depth = glm::dot(depth_row, c4);
        if (perspective) {
            out.projected_height_px = depth > 0.0f ? h * height_scale / std::max(depth, camera.near_plane) : 0.0f;
        } else {
            out.projected_height_px = h * height_scale;
        }
        const float w = glm::dot(r3, c4);
        if (w > 1e-6f) {
            out.eccentricity = std::max(std::fabs(glm::dot(r0, c4)), std::fabs(glm::dot(r1, c4))) / w;
        } else {
            out.eccentricity = kEccentricityBehind;
        }
        bool inside = true;
        for (int k = 0; k < 6; ++k) {
            const float support = glm::dot(planes[k], c4) + std::fabs(planes[k].y) * half_h + radius * plane_xz[k];
            inside = inside && support >= 0.0f;
        }
        out.visible = inside ? 1 : 0;
        out.speed = velocities.empty() ? 0.0f : glm::length(velocities[i].linear);
        out.importance = importance.empty() ? default_importance.value : importance[i].value;
    }
}

}  // namespace aloha
