#include "systems/frame/impostor_source.hpp"

#include "systems/geometry/spring_skin/skin_mesh.hpp"

namespace aloha {

uint8_t impostor_source_level(const GeometryController& gc) {
    for (const GeomMethod want : {GeomMethod::Layered, GeomMethod::SkinnedMesh, GeomMethod::Subdivided})
        for (uint8_t l = 0; l < gc.level_count(); ++l)
            if (gc.level(l).method == want) return l;
    return GeometryController::kNoLevel;
}

ImpostorBakeInput impostor_bake_input(const DrawType& draw, uint8_t level, std::span<const std::vector<glm::mat4>> poses,
                                      std::string name) {
    const GeometryController& gc = *draw.geometry;
    ImpostorBakeInput in;
    in.name = std::move(name);
    in.indices = gc.level_indices(level);
    in.uvs = gc.level_uvs(level);
    in.vertex_material = gc.level_vertex_materials(level);
    in.colours = gc.level_colours(level);
    in.materials = draw.materials;
    in.textures = draw.textures;
    bool double_sided = false;  // as the draw lists register the level (draw_lists.cpp)
    for (const SurfaceMaterial& m : draw.materials) double_sided = double_sided || m.double_sided;
    in.cull_back_faces = !double_sided;
    for (const std::vector<glm::mat4>& pose : poses) {
        ImpostorPose row;
        gc.reference_surface(PoseSource{pose.data(), pose.size()}, 0, level, row.positions);
        row.normals.resize(row.positions.size());
        if (!row.positions.empty()) accumulate_vertex_normals(row.positions, in.indices, row.normals);
        in.rows.push_back(std::move(row));
    }
    return in;
}

}  // namespace aloha
