#include "host/scene/world_diagnostics.hpp"

#include "engine/core/hash.hpp"
#include "host/scene/character_runtime.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace aloha {

uint64_t available_memory_bytes() {
    std::FILE* f = std::fopen("/proc/meminfo", "r");
    if (!f) return 0;
    char line[256];
    uint64_t kib = 0;
    while (std::fgets(line, sizeof line, f))
        if (std::sscanf(line, "MemAvailable: %lu kB", &kib) == 1) break;
    std::fclose(f);
    return kib * 1024;
}

std::vector<uint64_t> memory_per_level(const World& world) {
    std::vector<uint64_t> bytes(world.rules().table().geom_levels.size(), 0);
    const uint64_t base = sizeof(Transform) + sizeof(Velocity) + sizeof(Bounds) + sizeof(Importance) +
                          sizeof(CharacterRef) + sizeof(LodAttributes) + sizeof(LodRequest) + sizeof(LodState) +
                          sizeof(GeomLod) + sizeof(AnimLod) + sizeof(MotionState);
    for (size_t l = 0; l < bytes.size(); ++l) {
        for (size_t t = 0; t < world.type_count(); ++t) {
            const CharacterRuntime* rt = &world.runtime(t);
            const uint64_t pose = static_cast<uint64_t>(rt->joints()) *
                                  (sizeof(glm::vec3) * 2 + sizeof(glm::quat) + sizeof(glm::mat4) * 2);
            bytes[l] = std::max<uint64_t>(bytes[l], base + pose + rt->geometry->bytes_per_character(static_cast<uint8_t>(l)));
        }
    }
    return bytes;
}

uint64_t nonfinite_count(const World& world) {
    auto group = character_group(const_cast<World&>(world).registry());
    uint64_t bad = 0;
    auto check = [&](const float* v, size_t n) {
        for (size_t i = 0; i < n; ++i) bad += !std::isfinite(v[i]);
    };
    for (const Transform& t : group.span<Transform>()) check(&t.position.x, 3), check(&t.rotation.x, 4);
    for (size_t t = 0; t < world.type_count(); ++t) {
        const CharacterRuntime* rt = &world.runtime(t);
        for (uint32_t id = 0; id < rt->count; ++id) {
            const ConstPoseView pose = rt->motion->poses().view(id);
            check(&pose.model[0][0][0], pose.model.size() * 16);
            const SurfaceView surface = rt->geometry->surface(id);
            if (!surface.positions.empty()) check(&surface.positions[0].x, surface.positions.size() * 3);
            const std::span<const glm::mat4> boxes = rt->geometry->proxy_boxes(id);
            if (!boxes.empty()) check(&boxes[0][0][0], boxes.size() * 16);
        }
    }
    return bad;
}

uint64_t state_hash(const World& world) {
    auto group = character_group(const_cast<World&>(world).registry());
    StateHasher h;
    auto transforms = group.span<Transform>();
    auto states = group.span<LodState>();
    for (size_t t = 0; t < world.type_count(); ++t) {
        const CharacterRuntime* rt = &world.runtime(t);
        for (uint32_t id = 0; id < rt->count; ++id) {
            const uint32_t i = rt->element_of_character[id];
            h.add(transforms[i].position);
            h.add(transforms[i].rotation);
            h.add(states[i].geom_level);
            h.add(states[i].anim_level);
            const ConstPoseView pose = rt->motion->poses().view(id);
            h.add_span(pose.model);
        }
    }
    return h.value();
}

}  // namespace aloha
