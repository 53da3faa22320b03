// The viewer's cameras: the scene's own camera path (default), an orbit camera (drag to turn, wheel to
// zoom, right-drag to pan) and a fly camera (WASD + mouse look). Pure maths, no window or GPU.
#pragma once

#include "host/scene/scene_desc.hpp"
#include "systems/render/crowd_renderer.hpp"

#include <glm/glm.hpp>

namespace aloha::tool {

/// Which camera the viewer draws with.
enum class CameraMode : int { ScenePath = 0, Orbit = 1, Fly = 2 };

/// Number of camera modes (for cycling with a key).
inline constexpr int kCameraModeCount = 3;

/// Display name of a camera mode ("scene path", "orbit", "fly").
[[nodiscard]] const char* camera_mode_name(CameraMode mode);

/// Unit view direction for yaw (about +Y, 0 = looking along +Z) and pitch (up positive), radians.
[[nodiscard]] glm::vec3 direction_from_angles(float yaw, float pitch);

/// Most pitch either way (just under 90 degrees, so the view never aligns with the up axis).
inline constexpr float kMaxPitch = 1.5533430f;  // 89 degrees

/// Orbit camera: looks at `target` from `distance` along the direction given by yaw/pitch.
struct OrbitCamera {
    glm::vec3 target{0.0f, 1.0f, 0.0f};  ///< point looked at and turned about
    float yaw = 0.0f;                    ///< radians, see direction_from_angles
    float pitch = 0.0f;                  ///< radians, clamped to [-kMaxPitch, kMaxPitch]
    float distance = 5.0f;               ///< metres from target to eye, clamped to [0.2, 2000]

    /// Eye position: target - distance * direction.
    [[nodiscard]] glm::vec3 eye() const;
    /// Turns by a mouse drag of (dx, dy) pixels (0.005 rad per pixel; dragging right turns the view left).
    void rotate(float dx_px, float dy_px);
    /// Zooms by `wheel` notches (each notch scales the distance by 0.9).
    void zoom(float wheel);
    /// Moves the target in the view plane by a drag of (dx, dy) pixels, scaled with the distance.
    void pan(float dx_px, float dy_px);
};

/// Fly camera: free position, mouse look, WASD movement.
struct FlyCamera {
    glm::vec3 position{0.0f, 1.7f, 5.0f};  ///< eye
    float yaw = 0.0f;                      ///< radians, see direction_from_angles
    float pitch = 0.0f;                    ///< radians, clamped to [-kMaxPitch, kMaxPitch]
    float speed = 3.0f;                    ///< metres per second

    /// Unit forward direction.
    [[nodiscard]] glm::vec3 forward() const { return direction_from_angles(yaw, pitch); }
    /// Turns by a mouse move of (dx, dy) pixels (0.005 rad per pixel).
    void look(float dx_px, float dy_px);
    /// Moves for `dt` seconds along `input` = (right, up, forward) in [-1, 1] each, at speed * boost.
    void move(glm::vec3 input, float dt, float boost = 1.0f);
};

/// The viewer's camera state: mode, both free cameras and the lens.
struct ViewerCamera {
    CameraMode mode = CameraMode::ScenePath;  ///< camera in use
    OrbitCamera orbit;                        ///< used in Orbit mode
    FlyCamera fly;                            ///< used in Fly mode
    float fov_y_deg = 50.0f;                  ///< vertical field of view
    float near_plane = 0.1f;                  ///< > 0
    float far_plane = 1000.0f;                ///< > near_plane

    /// Copies the lens of `desc` and places both free cameras where `key` looks from (orbit target =
    /// key.target), so switching mode does not jump. Requires key.position != key.target.
    void reset_from(const CameraDesc& desc, const CameraKey& key);
    /// Eye and look-at point of the current mode; `scene_key` is the scene path's placement this frame.
    [[nodiscard]] CameraKey placement(const CameraKey& scene_key) const;
    /// View and projection (OpenGL convention) for a viewport of `aspect` = width / height (> 0).
    [[nodiscard]] RenderCamera matrices(const CameraKey& scene_key, float aspect) const;
};

}  // namespace aloha::tool
