// GeometryController's per-frame stages: update_muscles (the `muscle` system: shapes + tessellation)
// and update_skin (the `spring_skin` system: proxies, linear-blend skins, fat springs, skin, geomorph,
// refinement), each one loop over a level's characters. Every buffer written belongs to the
// character's slot or to the calling thread's scratch, so disjoint character lists may run
// concurrently; nothing is allocated once a thread's scratch has grown to the largest level. Job
// sizes are guaranteed by the slot layout (see build_level), so Validate() is only asserted (debug
// builds) and Run() called directly.
#include "systems/geometry/controller/controller_level.hpp"
#include "systems/geometry/muscle/muscle_shape_job.hpp"
#include "systems/geometry/muscle/muscle_tessellate_job.hpp"
#include "systems/geometry/controller/fat_regions.hpp"
#include "systems/geometry/spring_skin/fat_spring_frame.hpp"
#include "systems/geometry/spring_skin/geomorph.hpp"
#include "systems/geometry/spring_skin/peeled.hpp"
#include "systems/geometry/body_skin/blend_binding.hpp"
#include "systems/geometry/spring_skin/skin_mesh.hpp"

#include <array>
#include <cassert>
#include <vector>

namespace aloha {
namespace {

using Level = GeometryController::Level;

// Per-thread buffers for the refined surface when the level does not keep it.
struct FrameScratch {
    std::vector<glm::vec3> refined_positions, refined_normals;
};

std::span<glm::vec3> sized(std::vector<glm::vec3>& v, size_t n) {
    if (v.size() < n) v.resize(n);
    return std::span(v).first(n);
}

FrameScratch& frame_scratch() {
    thread_local FrameScratch scratch;
    return scratch;
}

// Shows a running morph of slot s: out = fresh + (left / total) * delta (out may alias fresh). On the
// first frame after the switch the deltas still hold the old surface and become old - fresh.
// Returns true when the morph was applied this frame.
bool apply_morph(SlotStore& st, uint32_t s, std::span<const glm::vec3> fresh, std::span<glm::vec3> out) {
    if (st.frames_left(s)[0] == 0) {
        st.shows_morph[s] = 0;
        return false;
    }
    const std::span<glm::vec3> d = st.deltas(s);
    if (st.pending[s]) {
        for (size_t i = 0; i < d.size(); ++i) d[i] -= fresh[i];
        st.pending[s] = 0;
    }
    const GeomorphJob morph{static_cast<uint32_t>(fresh.size()), fresh, d, st.frames_total(s), st.frames_left(s), out};
    assert(morph.Validate());
    morph.Run();
    st.shows_morph[s] = 1;
    return true;
}

void run_proxy(const CharacterGeometry& g, Level& L, uint32_t s, std::span<const glm::mat4> pose) {
    const RigidProxyJob job{pose, g.skeleton().parents(), g.proxy_radii(), 0.04f, L.store.boxes(s)};
    assert(job.Validate());
    job.Run();
}

void run_skinned(const CharacterGeometry& g, Level& L, uint32_t s, std::span<const glm::mat4> pose) {
    SlotStore& st = L.store;
    const std::span<glm::mat4> palette = st.palette(s);
    const std::span<const glm::mat4> inverse = L.real_mesh ? std::span<const glm::mat4>(g.mesh().inverse_bind) : g.inverse_rest_model();
    for (size_t j = 0; j < palette.size(); ++j) palette[j] = pose[j] * inverse[j];
    LinearBlendSkinJob job{palette, {}, {}, {}, {}, st.positions(s), st.normals(s)};
    set_lbs_source(g, L, job);
    assert(job.Validate());
    job.Run();
    // The skinned normals are kept where the limit moved a vertex: its moves are small next to a
    // triangle (a crease's fold, not a new shape), and the authored or bind normals light it better
    // than face normals of the coarse mesh would.
    limit_skin_strain(L.control_edges, st.positions(s));
    if (!apply_morph(st, s, st.positions(s), st.positions(s))) return;
    // While morphing, light the shape that is shown.
    accumulate_vertex_normals(st.positions(s), L.indices, st.normals(s));
}

void run_muscles(const CharacterGeometry& g, Level& L, uint32_t s, std::span<const glm::mat4> pose) {
    SlotStore& st = L.store;
    const MuscleShapeJob shape{&g.muscles(), pose, st.centres(s), st.rotations(s), st.radii(s)};
    assert(shape.Validate());
    shape.Run();
    const MuscleTessellateJob tess{L.tables, st.centres(s), st.rotations(s), st.radii(s), st.muscle_positions(s), st.muscle_normals(s)};
    assert(tess.Validate());
    tess.Run();
}

// Carries slot s's fat springs from their last placement to `now` (nullptr: none known; fat_spring_frame.hpp).
void carry_springs(Level& L, uint32_t s, const Transform* now, float dt) {
    SlotStore& st = L.store;
    if (!now) {
        st.placed[s] = 0;
        return;
    }
    if (st.placed[s] && st.spring_initialised(s)[0]) {
        const SpringReframeJob carry{spring_frame_change(st.placement[s], *now, dt),
                                     {st.spring_end(s), st.spring_velocity(s), st.spring_prev_rest(s), {}}};
        assert(carry.Validate());
        carry.Run();
    }
    st.placement[s] = *now;
    st.placed[s] = 1;
}

// `control_only`: the shown control surface alone (no morph, no normals, no refinement): the reference springs.
void run_layered_skin(const CharacterGeometry& g, Level& L, uint32_t s, const FatSpringParams& params,
                      std::span<const FatSpringParams> tunings, bool control_only = false) {
    SlotStore& st = L.store;
    // Skin vertices hang on blended muscle points; with the fat layer through the fat springs
    // (written to the spring ends), without it at the springs' rest ends (written to positions).
    const BlendSpringJob skin{L.theta_steps, L.phi_steps, g.muscle_count(), params, L.springs, st.muscle_positions(s),
                              st.muscle_normals(s), L.skin->bindings,
                              L.springs ? FatSpringStateView{st.spring_end(s), st.spring_velocity(s), st.spring_prev_rest(s),
                                                             st.spring_initialised(s)}
                                        : FatSpringStateView{st.positions(s), {}, {}, {}},
                              L.spring_region, L.spring_region.empty() ? std::span<const FatSpringParams>() : tunings};
    assert(skin.Validate());
    skin.Run();
    // The shown control surface: the skin strain limited (strain_limit.hpp). With the fat layer the
    // spring ends are copied first, so the limit shapes what is shown and never the springs' state.
    const std::span<glm::vec3> fresh = st.positions(s);
    if (L.springs) std::copy(st.spring_end(s).begin(), st.spring_end(s).end(), fresh.begin());
    limit_skin_strain(L.control_edges, fresh);
    if (control_only) return;
    if (!L.subdivision) {
        apply_morph(st, s, fresh, fresh);
        accumulate_vertex_normals(fresh, L.indices, st.normals(s));
        return;
    }
    // Subdivided: morph after refinement, on the surface that is displayed (the old level's displayed
    // surface was read at the refined vertices), so the switch starts on exactly what was shown.
    FrameScratch& scratch = frame_scratch();
    const size_t refined = L.subdivision->refined_vertex_count;
    const bool keep = L.keep_refined, morphing = st.frames_left(s)[0] > 0;
    const std::span<glm::vec3> positions = keep ? st.refined_positions(s) : sized(scratch.refined_positions, refined);
    const std::span<glm::vec3> normals = keep ? st.refined_normals(s) : sized(scratch.refined_normals, refined);
    // The displayed (refined) surface's edges are limited too: refinement averages the control edges
    // but can still fold a crease past the limits. While morphing, or after a limit moved the surface,
    // light the shape that is shown.
    const bool limited = refine_displayed(L, fresh, positions, morphing ? std::span<glm::vec3>() : normals);
    if (apply_morph(st, s, positions, positions) || limited) accumulate_vertex_normals(positions, L.indices, normals);
}

}  // namespace

void GeometryController::update_muscles(uint8_t level, std::span<const uint32_t> characters, const PoseSource& poses) {
    assert(level < levels_.size());
    Level& L = *levels_[level];
    if (!L.layered()) return;
    const CharacterGeometry& g = *geometry_;
    const size_t J = g.joint_count();
    for (const uint32_t c : characters) {
        assert(level_of(c) == level);
        run_muscles(g, L, slot_of_[c], poses.joints(c, J));
    }
}

void GeometryController::update_skin(uint8_t level, std::span<const uint32_t> characters, const PoseSource& poses, float dt) {
    update_skin(level, characters, poses, dt, PlacementSource{});
}

void GeometryController::update_skin(uint8_t level, std::span<const uint32_t> characters, const PoseSource& poses, float dt,
                                     const PlacementSource& placements) {
    assert(level < levels_.size() && dt > 0.0f);
    assert(placements.transforms.empty() || placements.elements.size() == characters.size());
    Level& L = *levels_[level];
    const CharacterGeometry& g = *geometry_;
    const size_t J = g.joint_count();
    FatSpringParams params = spring_params_;
    params.dt = dt;
    std::array<FatSpringParams, kMaxSpringTunings> tunings;  // per fat region (the muscle layout's): layered levels only
    if (L.layered()) region_spring_params(params, g.muscles().fat_regions, tunings);
    const bool skin_level = L.lod.method == GeomMethod::SkinnedMesh || L.layered();
    const uint64_t n = characters.size();
    L.work_characters.fetch_add(n, std::memory_order_relaxed);
    if (skin_level) L.work_vertices.fetch_add(n * L.control_vertices, std::memory_order_relaxed);
    if (L.springs) L.work_springs.fetch_add(n * L.control_vertices, std::memory_order_relaxed);
    for (size_t i = 0; i < characters.size(); ++i) {
        const uint32_t c = characters[i];
        assert(level_of(c) == level);
        const uint32_t s = slot_of_[c];
        if (L.store.pending[s]) start_morph(c, L, s);
        switch (L.lod.method) {
            case GeomMethod::Hidden:
            case GeomMethod::Impostor:
                break;
            case GeomMethod::RigidProxy:
                run_proxy(g, L, s, poses.joints(c, J));
                break;
            case GeomMethod::SkinnedMesh:
                run_skinned(g, L, s, poses.joints(c, J));
                break;
            case GeomMethod::Layered:
            case GeomMethod::Subdivided:
                if (L.springs)
                    carry_springs(L, s, placements.transforms.empty() ? nullptr : &placements.transforms[placements.elements[i]], dt);
                run_layered_skin(g, L, s, params, tunings);
                break;
        }
        L.store.valid[s] = 1;
    }
}

void GeometryController::start_morph(uint32_t character, Level& to, uint32_t to_slot) {
    // The left level's slot, kept by a cross-fade or as the morph's source, is posed every frame by update_fades,
    // which the frame runs before the skins: its surface at THIS frame's pose is where the entered level starts.
    // (Called in another order, the kept slot still holds the surface shown at the switch.) A start read when the
    // switch happened would be last frame's surface at last frame's pose (older still where the left level's
    // animation updates every few frames): morphing from it would replay the limbs' motion since then
    // (centimetres on a walker's swinging foot) on top of the two levels' difference of shape.
    uint8_t from_level = kNoLevel;
    uint32_t slot = LevelFade::kNoSlot;
    if (const LevelFade* f = fade(character); f && f->between_meshes && f->keeps_left()) {
        from_level = f->from_level;
        slot = f->kept_slot;
    } else {
        for (const MorphSource& m : morph_sources_)
            if (m.character == character) {
                from_level = m.from_level, slot = m.slot;
                break;
            }
    }
    if (from_level != kNoLevel && levels_[from_level]->store.valid[slot]) {
        capture_morph(*levels_[from_level], slot, to, to_slot);
        return;
    }
    // The kept slot went (advance_fades ran between the switch and this first update): no start, no morph.
    to.store.frames_total(to_slot)[0] = 0;
    to.store.frames_left(to_slot)[0] = 0;
    to.store.pending[to_slot] = 0;
}

void GeometryController::pose_kept_slot(Level& L, uint32_t slot, std::span<const glm::mat4> pose, const FatSpringParams& params,
                                        std::span<const FatSpringParams> tunings, float dt) {
    const CharacterGeometry& g = *geometry_;
    L.work_characters.fetch_add(1, std::memory_order_relaxed);
    switch (L.lod.method) {
        case GeomMethod::RigidProxy:
            run_proxy(g, L, slot, pose);
            break;
        case GeomMethod::SkinnedMesh:
            L.work_vertices.fetch_add(L.control_vertices, std::memory_order_relaxed);
            run_skinned(g, L, slot, pose);
            break;
        case GeomMethod::Layered:
        case GeomMethod::Subdivided:
            L.work_vertices.fetch_add(L.control_vertices, std::memory_order_relaxed);
            if (L.springs) L.work_springs.fetch_add(L.control_vertices, std::memory_order_relaxed);
            run_muscles(g, L, slot, pose);
            if (L.springs) carry_springs(L, slot, nullptr, dt);
            run_layered_skin(g, L, slot, params, tunings);
            break;
        case GeomMethod::Hidden:
        case GeomMethod::Impostor:
            break;
    }
}

void GeometryController::update_fades(const PoseSource& poses, float dt) {
    assert(dt > 0.0f);
    if (fades_.empty() && morph_sources_.empty()) return;
    const size_t J = geometry_->joint_count();
    FatSpringParams params = spring_params_;
    params.dt = dt;
    std::array<FatSpringParams, kMaxSpringTunings> tunings;  // per fat region
    region_spring_params(params, geometry_->muscles().fat_regions, tunings);
    for (const LevelFade& f : fades_)
        if (f.keeps_left())  // out of the impostor: the entered level's own stages run it
            pose_kept_slot(*levels_[f.from_level], f.kept_slot, poses.joints(f.character, J), params, tunings, dt);
    for (const MorphSource& m : morph_sources_)
        pose_kept_slot(*levels_[m.from_level], m.slot, poses.joints(m.character, J), params, tunings, dt);
}

void GeometryController::drop_reference_springs() {
    if (reference_level_ != kNoLevel && reference_level_ < levels_.size())
        for (const uint32_t c : reference_characters_) levels_[reference_level_]->store.release(reference_slot_[c]);
    for (const uint32_t c : reference_characters_) reference_slot_[c] = LevelFade::kNoSlot, reference_frames_[c] = 0;
    reference_characters_.clear();
    reference_level_ = kNoLevel;
}

void GeometryController::step_reference_springs(uint8_t reference_level, std::span<const uint32_t> characters, const PoseSource& poses,
                                                float dt, std::span<const Transform> placements) {
    assert(reference_level < levels_.size() && placements.size() == characters.size() && dt > 0.0f);
    if (reference_level != reference_level_) drop_reference_springs();
    Level& R = *levels_[reference_level];
    if (!R.springs) return;
    reference_level_ = reference_level;
    reference_slot_.resize(level_of_.size(), LevelFade::kNoSlot);
    reference_frames_.resize(level_of_.size(), 0);
    // Kept: the characters given that are at a mesh level now; the others' slots go back to the store.
    std::vector<uint8_t> keep(level_of_.size(), 0);
    for (const uint32_t c : characters)
        if (c < level_of_.size() && level_of_[c] != kNoLevel && levels_[level_of_[c]]->mesh_level) keep[c] = 1;
    std::vector<uint32_t> kept;
    for (const uint32_t c : reference_characters_) {
        if (keep[c]) {
            kept.push_back(c);
            continue;
        }
        R.store.release(reference_slot_[c]);
        reference_slot_[c] = LevelFade::kNoSlot;
        reference_frames_[c] = 0;
    }
    reference_characters_ = std::move(kept);
    const CharacterGeometry& g = *geometry_;
    FatSpringParams params = spring_params_;
    params.dt = dt;
    std::array<FatSpringParams, kMaxSpringTunings> tunings;
    region_spring_params(params, g.muscles().fat_regions, tunings);
    for (size_t i = 0; i < characters.size(); ++i) {
        const uint32_t c = characters[i];
        if (c >= keep.size() || !keep[c]) continue;
        uint32_t& s = reference_slot_[c];
        if (s == LevelFade::kNoSlot) {  // started at rest, as a level's springs start when it is entered
            s = R.store.acquire();
            std::fill(R.store.spring_initialised(s).begin(), R.store.spring_initialised(s).end(), uint8_t{0});
            R.store.placed[s] = 0;
            reference_characters_.push_back(c);
        }
        run_muscles(g, R, s, poses.joints(c, g.joint_count()));
        carry_springs(R, s, &placements[i], dt);
        run_layered_skin(g, R, s, params, tunings, /*control_only=*/true);
        ++reference_frames_[c];
    }
}

uint32_t GeometryController::reference_spring_frames(uint32_t character) const {
    return character < reference_frames_.size() ? reference_frames_[character] : 0;
}

void GeometryController::update(uint8_t level, std::span<const uint32_t> characters, const PoseSource& poses, float dt,
                                const PlacementSource& placements) {
    update_muscles(level, characters, poses);
    update_skin(level, characters, poses, dt, placements);
}

}  // namespace aloha
