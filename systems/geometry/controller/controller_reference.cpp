// Fidelity measurement: the stateless reference surface of a character at any level, and matched
// (current, reference) point pairs at the same place on the skin.
#include "systems/geometry/controller/controller_level.hpp"
#include "systems/geometry/muscle/muscle_shape_job.hpp"
#include "systems/geometry/muscle/muscle_tessellate_job.hpp"
#include "systems/geometry/spring_skin/peeled.hpp"
#include "systems/geometry/body_skin/blend_binding.hpp"
#include "systems/geometry/spring_skin/subdivision.hpp"

namespace aloha {

void GeometryController::control_surface(const Level& level, std::span<const glm::mat4> pose, std::vector<glm::vec3>& out,
                                         bool strain_limited) const {
    const CharacterGeometry& g = *geometry_;
    out.assign(level.control_vertices, glm::vec3(0.0f));
    if (!level.mesh_level) return;
    if (level.lod.method == GeomMethod::SkinnedMesh) {
        const std::span<const glm::mat4> inverse = level.real_mesh ? std::span<const glm::mat4>(g.mesh().inverse_bind) : g.inverse_rest_model();
        std::vector<glm::mat4> palette(pose.size());
        for (size_t j = 0; j < palette.size(); ++j) palette[j] = pose[j] * inverse[j];
        std::vector<glm::vec3> normals(out.size());
        LinearBlendSkinJob job{palette, {}, {}, {}, {}, out, normals};
        set_lbs_source(g, level, job);
        job.Run();
        if (strain_limited) limit_skin_strain(level.control_edges, out);
        return;
    }
    // Layered / Subdivided control surface with the fat springs at rest (their rest ends).
    const size_t M = g.muscle_count(), V = level.grid_vertices;
    std::vector<glm::vec3> centres(M), radii(M), mpos(M * V), mnrm(M * V);
    std::vector<glm::quat> rotations(M);
    const MuscleShapeJob shape{&g.muscles(), pose, centres, rotations, radii};
    shape.Run();
    const MuscleTessellateJob tess{level.tables, centres, rotations, radii, mpos, mnrm};
    tess.Run();
    const BlendSpringJob skin{level.theta_steps, level.phi_steps, g.muscle_count(), spring_params_, false, mpos, mnrm,
                              level.skin->bindings, {out, {}, {}, {}}};
    skin.Run();
    if (strain_limited) limit_skin_strain(level.control_edges, out);
}

void GeometryController::reference_surface(const PoseSource& poses, uint32_t character, uint8_t reference_level,
                                           std::vector<glm::vec3>& positions, bool strain_limited) const {
    const Level& R = *levels_.at(reference_level);
    positions.clear();
    if (!R.mesh_level) return;
    control_surface(R, poses.joints(character, geometry_->joint_count()), positions, strain_limited);
    if (!R.subdivision) return;
    std::vector<glm::vec3> refined(R.subdivision->refined_vertex_count);
    refine_displayed(R, positions, refined, {}, strain_limited);
    positions = std::move(refined);
}

std::span<const glm::vec3> GeometryController::fat_spring_ends(uint32_t character) const {
    const uint8_t l = level_of(character);
    if (l == kNoLevel || !levels_[l]->springs) return {};
    const uint32_t s = slot_of_[character];
    return levels_[l]->store.valid[s] ? levels_[l]->store.spring_end(s) : std::span<const glm::vec3>();
}

void GeometryController::deviation_pairs(const PoseSource& poses, uint32_t character, uint8_t reference_level,
                                         std::vector<glm::vec3>& current, std::vector<glm::vec3>& reference,
                                         std::vector<glm::vec3>* current_at_rest, std::vector<glm::vec3>* reference_moving) const {
    current.clear();
    reference.clear();
    if (current_at_rest) current_at_rest->clear();
    if (reference_moving) reference_moving->clear();
    const uint8_t l = level_of(character);
    if (l == kNoLevel) return;
    const Level& C = *levels_[l];
    const Level& R = *levels_.at(reference_level);
    const uint32_t s = slot_of_[character];
    if (!C.mesh_level || !R.mesh_level || !C.store.valid[s]) return;
    const std::span<const glm::vec3> shown = C.control(s);
    current.assign(shown.begin(), shown.end());
    const std::span<const glm::mat4> pose = poses.joints(character, geometry_->joint_count());
    if (current_at_rest) control_surface(C, pose, *current_at_rest);
    if (!C.simplified_map.corners.empty()) {  // where the simplified triangles show each vertex's part of the body
        C.simplified_map.apply(shown, current);
        if (current_at_rest) {
            const std::vector<glm::vec3> at_rest = *current_at_rest;
            C.simplified_map.apply(at_rest, *current_at_rest);
        }
    }
    std::vector<glm::vec3> ref_control;
    control_surface(R, pose, ref_control);
    // The reference springs as they moved: the reference level's shown control surface of their slot.
    std::span<const glm::vec3> moving;
    if (reference_moving && reference_level == reference_level_ && character < reference_slot_.size() &&
        reference_slot_[character] != LevelFade::kNoSlot)  // a slot is stepped when it is taken
        moving = R.control(reference_slot_[character]);
    if (C.same_skin(R)) {  // same vertices at both levels
        reference = std::move(ref_control);
        if (!moving.empty()) reference_moving->assign(moving.begin(), moving.end());
        return;
    }
    const auto& map = geometry_->skin_map(R.theta_steps, R.phi_steps, C.theta_steps, C.phi_steps);
    reference.resize(current.size());
    map.apply(ref_control, reference);
    if (moving.empty()) return;
    reference_moving->resize(current.size());
    map.apply(moving, *reference_moving);
}

}  // namespace aloha
