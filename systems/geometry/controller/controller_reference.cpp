// Fidelity measurement: the stateless reference surface of a character at any level, and matched
// (current, reference) point pairs at the same parametric location.
#include "systems/geometry/controller/controller_level.hpp"
#include "systems/geometry/muscle/muscle_shape_job.hpp"
#include "systems/geometry/muscle/muscle_tessellate_job.hpp"
#include "systems/geometry/spring_skin/grid_sample.hpp"
#include "systems/geometry/spring_skin/peeled.hpp"
#include "systems/geometry/spring_skin/skin_binding.hpp"
#include "systems/geometry/spring_skin/subdivision.hpp"

namespace aloha {

void GeometryController::control_surface(const Level& level, std::span<const glm::mat4> pose, std::vector<glm::vec3>& out) const {
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
        return;
    }
    // Layered / Subdivided control surface with the fat springs at rest (root + thickness * normal).
    const size_t M = g.muscle_count(), V = level.grid_vertices;
    std::vector<glm::vec3> centres(M), radii(M), mpos(M * V), mnrm(M * V);
    std::vector<glm::quat> rotations(M);
    const MuscleShapeJob shape{&g.muscles(), pose, centres, rotations, radii};
    shape.Run();
    const MuscleTessellateJob tess{level.tables, centres, rotations, radii, mpos, mnrm};
    tess.Run();
    if (level.real_mesh) {
        const BoundSkinJob bound{level.theta_steps, level.phi_steps, g.muscle_count(), mpos, mnrm, g.bindings(), out};
        bound.Run();
        return;
    }
    for (size_t m = 0; m < M; ++m) {
        const float h = g.muscles().fat_thickness[m];
        for (size_t i = m * V; i < (m + 1) * V; ++i) out[i] = mpos[i] + h * mnrm[i];
    }
}

void GeometryController::reference_surface(const PoseSource& poses, uint32_t character, uint8_t reference_level,
                                           std::vector<glm::vec3>& positions) const {
    const Level& R = *levels_.at(reference_level);
    positions.clear();
    if (!R.mesh_level) return;
    control_surface(R, poses.joints(character, geometry_->joint_count()), positions);
    if (!R.subdivision) return;
    std::vector<glm::vec3> refined(R.subdivision->refined_vertex_count);
    const SubdivideJob refine{R.subdivision, positions, refined, {}};
    refine.Run();
    positions = std::move(refined);
}

void GeometryController::deviation_pairs(const PoseSource& poses, uint32_t character, uint8_t reference_level,
                                         std::vector<glm::vec3>& current, std::vector<glm::vec3>& reference) const {
    current.clear();
    reference.clear();
    const uint8_t l = level_of(character);
    if (l == kNoLevel) return;
    const Level& C = *levels_[l];
    const Level& R = *levels_.at(reference_level);
    const uint32_t s = slot_of_[character];
    if (!C.mesh_level || !R.mesh_level || !C.store.valid[s]) return;
    const std::span<const glm::vec3> shown = C.control(s);
    current.assign(shown.begin(), shown.end());
    std::vector<glm::vec3> ref_control;
    control_surface(R, poses.joints(character, geometry_->joint_count()), ref_control);
    if (C.real_mesh) {  // same mesh vertices at every level
        reference = std::move(ref_control);
        return;
    }
    const uint32_t Vc = C.grid_vertices, Vr = R.grid_vertices, M = geometry_->muscle_count();
    reference.resize(current.size());
    for (uint32_t i = 0; i < Vc; ++i) {
        const GridParam param = grid_vertex_param(C.theta_steps, C.phi_steps, i);
        for (uint32_t m = 0; m < M; ++m) {
            const std::span<const glm::vec3> grid = std::span<const glm::vec3>(ref_control).subspan(size_t{m} * Vr, Vr);
            reference[size_t{m} * Vc + i] = sample_grid(grid, R.theta_steps, R.phi_steps, param);
        }
    }
}

}  // namespace aloha
