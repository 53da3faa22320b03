#include "host/tool/viewer_camera.hpp"

#include "engine/core/look_at.hpp"

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cmath>

namespace aloha::tool {

namespace {

constexpr float kRadiansPerPixel = 0.005f;
const glm::vec3 kUp{0.0f, 1.0f, 0.0f};

float clamp_pitch(float p) { return std::clamp(p, -kMaxPitch, kMaxPitch); }

// Yaw and pitch of unit-or-not direction `d` (inverse of direction_from_angles).
void angles_of(glm::vec3 d, float* yaw, float* pitch) {
    d = glm::normalize(d);
    *pitch = clamp_pitch(std::asin(std::clamp(d.y, -1.0f, 1.0f)));
    *yaw = std::atan2(d.x, d.z);
}

}  // namespace

const char* camera_mode_name(CameraMode mode) {
    switch (mode) {
        case CameraMode::ScenePath: return "scene path";
        case CameraMode::Orbit: return "orbit";
        case CameraMode::Fly: return "fly";
    }
    return "?";
}

glm::vec3 direction_from_angles(float yaw, float pitch) {
    const float c = std::cos(pitch);
    return {c * std::sin(yaw), std::sin(pitch), c * std::cos(yaw)};
}

glm::vec3 OrbitCamera::eye() const { return target - distance * direction_from_angles(yaw, pitch); }

void OrbitCamera::rotate(float dx_px, float dy_px) {
    yaw -= dx_px * kRadiansPerPixel;
    pitch = clamp_pitch(pitch + dy_px * kRadiansPerPixel);
}

void OrbitCamera::zoom(float wheel) { distance = std::clamp(distance * std::pow(0.9f, wheel), 0.2f, 2000.0f); }

void OrbitCamera::pan(float dx_px, float dy_px) {
    const glm::vec3 f = direction_from_angles(yaw, pitch);
    const glm::vec3 right = glm::normalize(glm::cross(f, kUp));
    const glm::vec3 up = glm::cross(right, f);
    const float scale = 0.0015f * distance;
    target += (-dx_px * right + dy_px * up) * scale;
}

void FlyCamera::look(float dx_px, float dy_px) {
    yaw -= dx_px * kRadiansPerPixel;
    pitch = clamp_pitch(pitch - dy_px * kRadiansPerPixel);
}

void FlyCamera::move(glm::vec3 input, float dt, float boost) {
    const glm::vec3 f = forward();
    const glm::vec3 right = glm::normalize(glm::cross(f, kUp));
    position += (input.x * right + input.y * kUp + input.z * f) * (speed * boost * dt);
}

void ViewerCamera::reset_from(const CameraDesc& desc, const CameraKey& key) {
    fov_y_deg = desc.fov_y_deg;
    near_plane = desc.near_plane;
    far_plane = desc.far_plane;
    const glm::vec3 d = key.target - key.position;
    orbit.target = key.target;
    orbit.distance = std::clamp(glm::length(d), 0.2f, 2000.0f);
    angles_of(d, &orbit.yaw, &orbit.pitch);
    fly.position = key.position;
    angles_of(d, &fly.yaw, &fly.pitch);
}

CameraKey ViewerCamera::placement(const CameraKey& scene_key) const {
    CameraKey k = scene_key;
    if (mode == CameraMode::Orbit) {
        k.position = orbit.eye();
        k.target = orbit.target;
    } else if (mode == CameraMode::Fly) {
        k.position = fly.position;
        k.target = fly.position + fly.forward();
    }
    return k;
}

RenderCamera ViewerCamera::matrices(const CameraKey& scene_key, float aspect) const {
    const CameraKey k = placement(scene_key);
    RenderCamera c;
    c.view = look_at_y_up(k.position, k.target);
    c.proj = glm::perspective(glm::radians(fov_y_deg), aspect, near_plane, far_plane);
    return c;
}

}  // namespace aloha::tool
