// The lod_attributes system: per character, what the knowledge base tests (distance, size on
// screen, eccentricity, speed, visibility, importance), computed from the transform and a camera.
#pragma once

#include "components/lod.hpp"
#include "components/transform.hpp"

#include <glm/glm.hpp>

#include <span>
#include <string>
#include <vector>

namespace aloha {

/// The camera the attributes are measured against. `projection` is a right-handed OpenGL/GLM-style
/// perspective (glm::perspective; depth clip range irrelevant) or orthographic matrix; `view` maps
/// world to camera space (camera looks down -Z). Requires viewport > 0 and 0 < near < far.
struct LodCamera {
    glm::vec3 position{0.0f};          ///< world position of the eye
    glm::mat4 view{1.0f};              ///< world -> camera
    glm::mat4 projection{1.0f};        ///< camera -> clip
    glm::vec2 viewport_px{1280.0f, 720.0f}; ///< viewport width, height in pixels
    float near_plane = 0.1f;           ///< metres, > 0
    float far_plane = 1000.0f;         ///< metres, > near_plane
};

/// Builds a LodCamera looking from `eye` at `target` (Y up) with vertical field of view `fovy_rad`.
/// Requires eye != target, 0 < fovy < pi, viewport > 0, 0 < near < far.
[[nodiscard]] LodCamera make_lod_camera(glm::vec3 eye, glm::vec3 target, float fovy_rad, glm::vec2 viewport_px,
                                        float near_plane, float far_plane);

/// Eccentricity written for characters whose centre is at or behind the eye plane (w <= 0).
inline constexpr float kEccentricityBehind = 1.0e6f;

/// Computes LodAttributes for a contiguous range of characters.
///
/// Model: a character's bounds are a vertical (world Y) cylinder standing on `Transform::position`,
/// radius `Bounds::radius * scale`, height `Bounds::height * scale`; its centre is half-way up.
/// - distance: |centre - camera.position|.
/// - projected_height_px: h * P[1][1] * viewport_h / (2 * z) with z the view-space depth of the
///   centre (the standard h * viewport_h / (2 z tan(fovy/2)), since P[1][1] = 1/tan(fovy/2)); z is
///   clamped to >= near; 0 when z <= 0 (behind the eye). Orthographic: h * P[1][1] * viewport_h / 2.
/// - eccentricity: max(|x_ndc|, |y_ndc|) of the centre: 0 at the view centre, exactly 1 on a side
///   plane of the frustum, > 1 outside; kEccentricityBehind when the centre is behind the eye.
/// - speed: |Velocity::linear|. importance: Importance::value.
/// - visible: 1 when the cylinder is not entirely outside any of the 6 frustum planes (exact
///   cylinder-vs-plane support distance; conservative near frustum corners, like every plane test).
struct LodAttributesJob {
    std::span<const Transform> transforms;    ///< required, n entries
    std::span<const Velocity> velocities;     ///< n entries, or empty (speed 0)
    std::span<const Bounds> bounds;           ///< n entries, or empty (default Bounds)
    std::span<const Importance> importance;   ///< n entries, or empty (default Importance)
    LodCamera camera;                         ///< see LodCamera requirements
    std::span<LodAttributes> output;          ///< n entries, written

    /// Checks sizes and the camera; appends one message per failure to `errors` when given.
    bool Validate(std::vector<std::string>* errors = nullptr) const;
    /// Writes output[i] for every i. Requires Validate().
    void Run() const;
};

}  // namespace aloha
