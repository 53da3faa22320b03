// Impostor draw order (systems/render/impostor_order.hpp).
#include "systems/render/impostor_order.hpp"

#include <glm/gtc/matrix_access.hpp>

#include <algorithm>

namespace aloha {

void sort_nearest_first(std::span<uint32_t> order, std::span<const float> depth) {
    std::sort(order.begin(), order.end(), [&](uint32_t a, uint32_t b) { return depth[a] < depth[b] || (depth[a] == depth[b] && a < b); });
}

void sort_impostors_nearest_first(std::span<const ImpostorInstance> impostors, const glm::mat4& view, std::vector<uint32_t>& order,
                                  std::vector<float>& depth) {
    const auto n = static_cast<uint32_t>(impostors.size());
    const glm::vec4 forward = glm::row(view, 2);  // view-space z of a world point (negative ahead)
    depth.resize(n);
    order.resize(n);
    for (uint32_t i = 0; i < n; ++i) {
        depth[i] = -glm::dot(forward, glm::vec4(glm::vec3(impostors[i].position_scale), 1.0f));
        order[i] = i;
    }
    for (uint32_t first = 0; first < n;) {
        uint32_t end = first + 1;
        while (end < n && impostors[end].atlas == impostors[first].atlas) ++end;
        sort_nearest_first(std::span(order).subspan(first, end - first), depth);
        first = end;
    }
}

}  // namespace aloha
