// World::skin_sample and World::pin_geom_level: one character's displayed body in world space (the
// mesh its geometric level draws, or its rigid proxy boxes, plus its skeleton), and holding one
// character at a chosen geometric level (aloha export --out FILE.glb [--level L]).
#include "host/scene/world.hpp"

#include "host/scene/character_runtime.hpp"
#include "systems/frame/placement.hpp"

#include <array>
#include <cassert>

namespace aloha {

namespace {

// The unit cube [-1, 1]^3 as 6 faces of 4 corners (counter-clockwise seen from outside) and their normals.
constexpr std::array<std::array<glm::vec3, 4>, 6> kCubeFaces = {{
    {{{1, -1, -1}, {1, 1, -1}, {1, 1, 1}, {1, -1, 1}}},
    {{{-1, -1, 1}, {-1, 1, 1}, {-1, 1, -1}, {-1, -1, -1}}},
    {{{-1, 1, -1}, {-1, 1, 1}, {1, 1, 1}, {1, 1, -1}}},
    {{{-1, -1, 1}, {-1, -1, -1}, {1, -1, -1}, {1, -1, 1}}},
    {{{-1, -1, 1}, {1, -1, 1}, {1, 1, 1}, {-1, 1, 1}}},
    {{{1, -1, -1}, {-1, -1, -1}, {-1, 1, -1}, {1, 1, -1}}},
}};
constexpr std::array<glm::vec3, 6> kCubeNormals = {{{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}}};

// Appends box `box` (cube [-1, 1]^3 -> world) as 24 vertices and 12 triangles.
void append_box(const glm::mat4& box, SkinSample& out) {
    const glm::mat3 normal_matrix = glm::transpose(glm::inverse(glm::mat3(box)));
    for (size_t f = 0; f < kCubeFaces.size(); ++f) {
        const auto base = static_cast<uint32_t>(out.positions.size());
        for (const glm::vec3& corner : kCubeFaces[f]) {
            out.positions.push_back(glm::vec3(box * glm::vec4(corner, 1.0f)));
            out.normals.push_back(glm::normalize(normal_matrix * kCubeNormals[f]));
        }
        for (const uint32_t k : {0u, 1u, 2u, 0u, 2u, 3u}) out.indices.push_back(base + k);
    }
}

}  // namespace

std::pair<size_t, uint32_t> World::spawn_character(uint32_t index) const {
    uint32_t first = 0;
    size_t t = 0;
    while (t < types_.size() && index >= first + types_[t]->count) first += types_[t++]->count;
    assert(t < types_.size() && "spawn_character: index out of range");
    return {t, index - first};
}

void World::skin_sample(uint32_t index, SkinSample& out) const {
    const auto [t, id] = spawn_character(index);
    const CharacterRuntime& rt = *types_[t];
    auto group = character_group(const_cast<Registry&>(registry_));
    out.type = static_cast<uint16_t>(t);
    out.id = id;
    out.placement = world_matrix(group.span<Transform>()[rt.element_of_character[id]]);
    out.positions.clear();
    out.normals.clear();
    out.indices.clear();
    const GeometryController& gc = *rt.geometry;
    out.level = gc.level_of(id);
    out.method = out.level == GeometryController::kNoLevel ? GeomMethod::Hidden : gc.level(out.level).method;
    const glm::mat4& world = out.placement;
    const glm::mat3 rotate = glm::mat3(world);  // rotation times a uniform scale: normals only need normalising
    if (const SurfaceView surface = gc.surface(id); !surface.positions.empty()) {
        for (const glm::vec3& p : surface.positions) out.positions.push_back(glm::vec3(world * glm::vec4(p, 1.0f)));
        for (const glm::vec3& n : surface.normals) out.normals.push_back(glm::normalize(rotate * n));
        const std::span<const uint32_t> indices = gc.level_indices(out.level);
        out.indices.assign(indices.begin(), indices.end());
    } else if (const std::span<const glm::mat4> boxes = gc.proxy_boxes(id); !boxes.empty()) {
        for (const uint16_t j : rt.proxy_joints) append_box(world * boxes[j], out);  // the boxes the draw lists draw
    }
    const ConstPoseView pose = rt.motion->poses().view(id);
    out.joint_names.assign(rt.type.skeleton.names().begin(), rt.type.skeleton.names().end());
    out.parents.assign(rt.type.skeleton.parents().begin(), rt.type.skeleton.parents().end());
    out.joints.resize(pose.model.size());
    for (size_t j = 0; j < pose.model.size(); ++j) out.joints[j] = world * pose.model[j];
}

Status World::pin_geom_level(uint32_t index, uint8_t level) {
    const size_t count = character_count();
    if (index >= count)
        return option_error(scene_.file, "character",
                            "character " + std::to_string(index) + " is past the crowd: the scene has " + std::to_string(count) +
                                " characters (indices 0 to " + std::to_string(count - 1) + ")");
    const size_t levels = rules_.table().geom_levels.size();
    if (level >= levels)
        return option_error(rules_.table().source.empty() ? scene_.rules : rules_.table().source, "level",
                            "geometric level " + std::to_string(level) + " is past the rule table's " + std::to_string(levels) +
                                " geometric levels (0 to " + std::to_string(levels - 1) + ")");
    pin_ = std::pair{index, level};
    return {};
}

void World::apply_level_pin(std::span<LodRequest> requests, std::span<LodState> states) const {
    if (!pin_) return;
    const auto [t, id] = spawn_character(pin_->first);
    const uint32_t e = types_[t]->element_of_character[id];
    requests[e].geom_level = pin_->second;
    states[e].always_full = 1;  // the budget never demotes it
}

}  // namespace aloha
