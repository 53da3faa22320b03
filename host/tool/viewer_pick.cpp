#include "host/tool/viewer_pick.hpp"

#include <algorithm>
#include <limits>

namespace aloha::tool {

namespace {

// Distance from point p to segment [a, b] in 2D.
float distance_to_segment(glm::vec2 p, glm::vec2 a, glm::vec2 b) {
    const glm::vec2 ab = b - a;
    const float len2 = glm::dot(ab, ab);
    const float s = len2 > 0.0f ? std::clamp(glm::dot(p - a, ab) / len2, 0.0f, 1.0f) : 0.0f;
    return glm::length(p - (a + s * ab));
}

}  // namespace

bool project_to_pixels(const RenderCamera& camera, glm::vec2 viewport, glm::vec3 p, glm::vec2* out) {
    const glm::vec4 clip = camera.proj * camera.view * glm::vec4(p, 1.0f);
    if (clip.w <= 0.0f) return false;
    const glm::vec2 ndc = glm::vec2(clip) / clip.w;  // OpenGL: y up
    *out = {(ndc.x * 0.5f + 0.5f) * viewport.x, (0.5f - ndc.y * 0.5f) * viewport.y};
    return true;
}

int pick_character(std::span<const Transform> transforms, std::span<const Bounds> bounds, const RenderCamera& camera,
                   glm::vec2 viewport, glm::vec2 mouse_px, float max_px) {
    int best = -1;
    float best_px = max_px;
    float best_depth = std::numeric_limits<float>::infinity();
    const size_t n = std::min(transforms.size(), bounds.size());
    for (size_t i = 0; i < n; ++i) {
        const Transform& t = transforms[i];
        const glm::vec3 base = t.position;
        const glm::vec3 top = base + glm::vec3(0.0f, bounds[i].height * t.scale, 0.0f);
        glm::vec2 a, b;
        if (!project_to_pixels(camera, viewport, base, &a) || !project_to_pixels(camera, viewport, top, &b)) continue;
        const float d = distance_to_segment(mouse_px, a, b);
        const float depth = -(camera.view * glm::vec4(base, 1.0f)).z;
        if (d < best_px || (d == best_px && depth < best_depth)) {
            best = static_cast<int>(i);
            best_px = d;
            best_depth = depth;
        }
    }
    return best;
}

int find_character(std::span<const CharacterRef> refs, CharacterRef ref) {
    for (size_t i = 0; i < refs.size(); ++i)
        if (refs[i].type == ref.type && refs[i].id == ref.id) return static_cast<int>(i);
    return -1;
}

void marker_lines(const Transform& t, const Bounds& bounds, glm::vec4 colour, std::vector<LineSegment>& out) {
    const float r = bounds.radius * t.scale;
    const float h = bounds.height * t.scale;
    const glm::vec3 p = t.position;
    const glm::vec3 c[4] = {{-r, 0, -r}, {r, 0, -r}, {r, 0, r}, {-r, 0, r}};
    const glm::vec3 up{0.0f, h, 0.0f};
    for (int k = 0; k < 4; ++k) {
        const glm::vec3 a = p + c[k], b = p + c[(k + 1) % 4];
        out.push_back({a, b, colour});
        out.push_back({a + up, b + up, colour});
        out.push_back({a, a + up, colour});
    }
}

}  // namespace aloha::tool
