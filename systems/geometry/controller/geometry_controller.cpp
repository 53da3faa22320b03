// GeometryController: level building, slot management, level switches with geomorph capture, and
// the per-character outputs. The per-frame work is in controller_update.cpp.
#include "systems/geometry/controller/geometry_controller.hpp"

#include "systems/geometry/controller/body_texture.hpp"
#include "systems/geometry/controller/controller_level.hpp"
#include "systems/geometry/controller/fat_regions.hpp"
#include "systems/geometry/controller/simplified_indices.hpp"
#include "systems/geometry/spring_skin/skin_mesh.hpp"

#include <algorithm>
#include <cassert>

namespace aloha {

bool same_level_shape(const GeomLod& a, const GeomLod& b) {
    if (a.method != b.method) return false;
    switch (a.method) {
        case GeomMethod::Hidden:
        case GeomMethod::RigidProxy:
        case GeomMethod::Impostor:
            return true;
        case GeomMethod::SkinnedMesh:
            return a.theta_steps == b.theta_steps && a.phi_steps == b.phi_steps && a.simplify_error == b.simplify_error &&
                   a.lit_per_pixel == b.lit_per_pixel;
        case GeomMethod::Layered:
            return a.theta_steps == b.theta_steps && a.phi_steps == b.phi_steps;
        case GeomMethod::Subdivided:
            return a.theta_steps == b.theta_steps && a.phi_steps == b.phi_steps && a.subdiv_level == b.subdiv_level;
    }
    return false;
}

GeometryController::GeometryController(const CharacterGeometry& geometry, std::span<const GeomLod> levels, uint32_t capacity,
                                       bool keep_refined_surfaces)
    : geometry_(&geometry), level_of_(capacity, kNoLevel), slot_of_(capacity, 0),
      fade_index_(capacity, LevelFade::kNoSlot), keep_refined_(keep_refined_surfaces) {
    set_levels(levels);
}

GeometryController::~GeometryController() = default;

namespace {

// UVs, materials and colours of the level's displayed vertices: those of its control surface (the real mesh,
// or the generated body UVs of the skin layer at rest), carried through the subdivision stencils.
void set_surface_attributes(const CharacterGeometry& g, GeometryController::Level& level) {
    std::vector<glm::vec2> uvs;
    std::vector<uint16_t> materials;
    std::vector<glm::vec4> colours;
    if (level.real_mesh) {
        uvs = g.mesh().uvs;
        materials = g.mesh().vertex_material;
        colours = g.mesh().colours;
    } else {
        uvs = body_skin_uvs(g.skeleton(), g.rest_model(), g.muscles(), level.skin->rest_positions, level.skin->dominant_muscle,
                            level.skin->indices);
    }
    const SubdivisionTopology* sub = level.subdivision;
    if (!sub) {
        level.uvs = std::move(uvs);
        level.vertex_material = std::move(materials);
        level.colours = std::move(colours);
        return;
    }
    // Refined vertex i = sum of weights * control vertices; primitives share no vertex, so every
    // stencil stays within one material.
    if (!uvs.empty()) level.uvs.assign(sub->refined_vertex_count, glm::vec2(0.0f));
    if (!materials.empty()) level.vertex_material.assign(sub->refined_vertex_count, 0);
    if (!colours.empty()) level.colours.assign(sub->refined_vertex_count, glm::vec4(0.0f));
    for (uint32_t i = 0; i < sub->refined_vertex_count; ++i) {
        for (uint32_t k = sub->offsets[i]; k < sub->offsets[i + 1]; ++k) {
            if (!uvs.empty()) level.uvs[i] += sub->weights[k] * uvs[sub->indices[k]];
            if (!colours.empty()) level.colours[i] += sub->weights[k] * colours[sub->indices[k]];
        }
        if (!materials.empty() && sub->offsets[i + 1] > sub->offsets[i]) level.vertex_material[i] = materials[sub->indices[sub->offsets[i]]];
    }
}

}  // namespace

std::unique_ptr<GeometryController::Level> GeometryController::build_level(const GeomLod& lod, uint8_t index,
                                                                           uint8_t revision) const {
    const CharacterGeometry& g = *geometry_;
    const uint32_t J = g.joint_count(), M = g.muscle_count();
    const bool real = g.has_mesh();
    // Rule files are validated by their loader; clamp here so a bad table cannot break the grids.
    const uint32_t T = std::max<uint32_t>(3, lod.theta_steps), P = std::max<uint32_t>(2, lod.phi_steps);
    const uint32_t V = grid_vertex_count(T, P);
    // The skin layer: the real mesh's vertices bound at (T, P), or the generated skin at (T, P).
    const bool mesh_method = lod.method == GeomMethod::SkinnedMesh || lod.method == GeomMethod::Layered ||
                             lod.method == GeomMethod::Subdivided;
    const SkinLayer* skin = mesh_method && M > 0 && (!real || lod.method != GeomMethod::SkinnedMesh) ? &g.skin_layer(T, P) : nullptr;
    const uint32_t control = real ? static_cast<uint32_t>(g.mesh().positions.size())
                                  : (skin ? static_cast<uint32_t>(skin->rest_positions.size()) : 0);
    const bool springs = (lod.layers & kLayerFat) != 0;

    SlotLayout layout;
    const SubdivisionTopology* subdivision = nullptr;
    switch (lod.method) {
        case GeomMethod::Hidden:
        case GeomMethod::Impostor:  // drawn from the type's atlas (systems/render/impostor_atlas.hpp)
            break;
        case GeomMethod::RigidProxy:
            layout.boxes = J;
            break;
        case GeomMethod::SkinnedMesh:
            layout.palette = J;
            layout.control = control;
            layout.morph = control;
            layout.control_normals = control;
            break;
        case GeomMethod::Layered:
        case GeomMethod::Subdivided:
            layout.shapes = M;
            layout.muscle_vertices = M * V;
            if (springs) {
                layout.springs = control;
                layout.spring_flags = 1;
            }
            layout.control = control;
            if (lod.method == GeomMethod::Layered) {
                layout.control_normals = control;
                layout.morph = control;
            } else {
                // Morphs run on the refined surface (the one displayed); none when it is not kept.
                subdivision = &g.subdivision(T, P, std::min<uint32_t>(lod.subdiv_level, 4));
                layout.refined = keep_refined_ ? subdivision->refined_vertex_count : 0;
                layout.morph = layout.refined;
            }
            break;
    }
    auto level = std::make_unique<Level>(layout);
    level->lod = lod;
    level->index = index;
    level->revision = revision;
    level->mesh_level = layout.control > 0;
    level->real_mesh = real;
    level->keep_refined = keep_refined_;
    level->theta_steps = T;
    level->phi_steps = P;
    level->grid_vertices = V;
    level->control_vertices = layout.control;
    level->display_vertices = subdivision ? subdivision->refined_vertex_count : layout.control;
    level->subdivision = subdivision;
    level->display_key = {real ? 0 : T, real ? 0 : P, subdivision ? std::min<uint32_t>(lod.subdiv_level, 4) : 0};
    if (level->layered()) level->tables = &g.tables(T, P);
    level->skin = skin;
    level->springs = level->layered() && springs;
    if (level->springs) level->spring_region = vertex_fat_regions(skin->bindings, g.muscles());
    if (subdivision) {
        level->indices = subdivision->triangles;
    } else if (level->mesh_level) {
        level->indices = real ? std::span<const uint32_t>(g.mesh().indices) : std::span<const uint32_t>(skin->indices);
        if (lod.method == GeomMethod::SkinnedMesh && lod.simplify_error > 0.0f) {
            // Fewer triangles over the same vertices (simplified_indices.hpp): the skinning, the UVs and a
            // geomorph to or from the full list (same display_key: vertex by vertex) are unchanged.
            const std::span<const glm::vec3> rest = real ? std::span<const glm::vec3>(g.mesh().positions)
                                                         : std::span<const glm::vec3>(skin->rest_positions);
            level->simplified_indices = g.simplified(rest, level->indices, lod.simplify_error);
            level->indices = level->simplified_indices;
            level->simplified_map = map_surface(rest, level->simplified_indices, rest);
        }
    }
    if (level->mesh_level) {
        set_surface_attributes(g, *level);
        // Strain limiting measures edges against the surface at the skeleton's rest pose (what the
        // level shows there: for a real mesh its skinned rest positions, not the bind-pose file data).
        std::vector<glm::vec3> rest;
        std::vector<uint32_t> triangles;
        g.rest_surface({level->display_key.theta_steps, level->display_key.phi_steps, 0}, rest, triangles);
        level->control_edges = build_skin_edges(triangles, rest);
        if (subdivision) {
            g.rest_surface(level->display_key, rest, triangles);
            level->refined_edges = build_skin_edges(triangles, rest);
        }
    }
    return level;
}

void GeometryController::set_levels(std::span<const GeomLod> levels) {
    assert(!levels.empty() && levels.size() < kNoLevel);
    end_fades();  // kept slots live in levels that may be rebuilt: the running cross-fades end here
    end_morph_sources();
    drop_reference_springs();  // so do the reference springs' slots
    // Every generated skin the levels use, simplified in one pass (build_level then finds them built).
    if (geometry_->muscle_count() > 0 && !geometry_->has_mesh()) {
        std::vector<std::pair<uint32_t, uint32_t>> skins;
        for (const GeomLod& lod : levels)
            if (lod.method == GeomMethod::SkinnedMesh || lod.method == GeomMethod::Layered || lod.method == GeomMethod::Subdivided)
                skins.emplace_back(std::max<uint32_t>(3, lod.theta_steps), std::max<uint32_t>(2, lod.phi_steps));
        geometry_->prepare_skin_layers(skins);
    }
    std::vector<std::unique_ptr<Level>> next(levels.size());
    std::vector<uint8_t> kept(levels.size(), 0);
    for (size_t i = 0; i < levels.size(); ++i) {
        const auto index = static_cast<uint8_t>(i);
        if (i < levels_.size() && same_level_shape(levels_[i]->lod, levels[i])) {
            next[i] = std::move(levels_[i]);
            next[i]->lod = levels[i];
            kept[i] = 1;
        } else {
            const uint8_t revision = i < levels_.size() ? static_cast<uint8_t>(levels_[i]->revision + 1) : 0;
            next[i] = build_level(levels[i], index, revision);
        }
    }
    for (size_t c = 0; c < level_of_.size(); ++c) {
        const uint8_t old = level_of_[c];
        if (old == kNoLevel) continue;
        const auto now = static_cast<uint8_t>(std::min<size_t>(old, levels.size() - 1));
        if (now == old && kept[old]) continue;
        // The old slot lives in a level being dropped or rebuilt: it goes away with that level.
        SlotStore& store = next[now]->store;
        const uint32_t s = store.acquire();
        std::fill(store.spring_initialised(s).begin(), store.spring_initialised(s).end(), uint8_t{0});
        level_of_[c] = now;
        slot_of_[c] = s;
    }
    levels_ = std::move(next);
    // The correspondences a geomorph reads, built now (in parallel) rather than at the first switch
    // (issue 18: no hitch at a switch): between any two unrefined skins (cheap; rules may skip levels)
    // and between neighbouring levels when one is refined (a map onto a refined surface takes a few
    // hundred milliseconds; a switch that skips past a subdivided level builds its map when it happens).
    std::vector<std::pair<SkinSurfaceKey, SkinSurfaceKey>> pairs;
    for (size_t i = 0; i < levels_.size(); ++i)
        for (size_t j = 0; j < levels_.size(); ++j) {
            const Level& a = *levels_[i];
            const Level& b = *levels_[j];
            if (i == j || !a.mesh_level || !b.mesh_level || a.display_key == b.display_key || b.store.layout().morph == 0) continue;
            const bool neighbours = i + 1 == j || j + 1 == i;
            if (neighbours || (a.display_key.subdivision == 0 && b.display_key.subdivision == 0)) pairs.emplace_back(a.display_key, b.display_key);
        }
    geometry_->prepare_surface_maps(pairs);
}

void GeometryController::ensure_capacity(uint32_t character) {
    if (character < level_of_.size()) return;
    const size_t n = std::max<size_t>(size_t{character} + 1, 2 * level_of_.size());
    level_of_.resize(n, kNoLevel);
    slot_of_.resize(n, 0);
    fade_index_.resize(n, LevelFade::kNoSlot);
}

void GeometryController::capture_morph(const Level& from, uint32_t from_slot, Level& to, uint32_t to_slot) {
    // The old DISPLAYED surface: the refined one at a Subdivided level (refined again here when the
    // level does not keep it), else the control surface.
    std::span<const glm::vec3> old = from.control(from_slot);
    std::vector<glm::vec3> refined;
    if (from.subdivision) {
        if (from.keep_refined) {
            old = from.store.refined_positions(from_slot);
        } else {
            refined.resize(from.subdivision->refined_vertex_count);
            refine_displayed(from, old, refined);
            old = refined;
        }
    }
    const std::span<glm::vec3> target = to.store.deltas(to_slot);
    if (to.display_key == from.display_key) {  // same displayed vertices: one by one
        std::copy(old.begin(), old.end(), target.begin());
        return;
    }
    // Different surfaces (resolutions of the generated skin, refined or not): the old surface read at
    // each new displayed vertex's rest-pose closest point.
    geometry_->surface_map(from.display_key, to.display_key).apply(old, target);
}

void GeometryController::begin_level(uint32_t character, uint8_t level, int8_t previous_level, uint16_t geomorph_frames,
                                     uint16_t fade_frames) {
    assert(level < levels_.size());
    (void)previous_level;  // the controller's own record is authoritative
    ensure_capacity(character);
    const uint8_t old = level_of_[character];
    if (old == level) return;
    end_fade(character);  // a switch during a cross-fade ends it (its kept slot released)
    end_morph_source(character);
    Level& to = *levels_[level];
    const uint32_t s = to.store.acquire();
    std::fill(to.store.spring_initialised(s).begin(), to.store.spring_initialised(s).end(), uint8_t{0});
    to.store.frames_total(s)[0] = 0;
    to.store.frames_left(s)[0] = 0;
    if (old != kNoLevel) {
        Level& from = *levels_[old];
        const uint32_t os = slot_of_[character];
        bool morphing = false;
        // Two linear-blend levels over the same vertices (one with a simplified triangle list) put them at the same
        // positions for the same pose: no difference of shape to slide over, only the limbs' motion since the
        // surface was last shown (frames ago where the animation updates every few), which a morph would replay.
        const bool same_positions = from.lod.method == GeomMethod::SkinnedMesh && to.lod.method == GeomMethod::SkinnedMesh &&
                                    from.display_key == to.display_key;
        if (geomorph_frames > 0 && from.mesh_level && to.mesh_level && from.store.valid[os] && to.store.layout().morph > 0 &&
            !same_positions) {
            morphing = true;  // its start is read from the kept left slot at the first update (start_morph)
            to.store.frames_total(s)[0] = geomorph_frames;
            to.store.frames_left(s)[0] = geomorph_frames;
            to.store.pending[s] = 1;
        }
        // Into or out of the impostor level, or between mesh levels showing different surfaces: a cross-fade
        // (LevelFade); into the impostor or a mesh level, the left level's slot stays while fading if it has been shown.
        const bool between_meshes = mesh_crossfades(old, level);
        const bool keep = to.lod.method == GeomMethod::Impostor || between_meshes;
        // A morph whose left slot no fade keeps keeps it as its source until the next advance_fades.
        auto leave = [&] {
            if (morphing) morph_sources_.push_back({character, old, os});
            else from.store.release(os);
        };
        if (fade_frames >= 2 && crossfades(old, level) && (!keep || from.store.valid[os])) {
            begin_fade(character, old, keep ? os : LevelFade::kNoSlot, fade_frames, between_meshes);
            if (!keep) leave();
        } else {
            leave();
        }
    }
    level_of_[character] = level;
    slot_of_[character] = s;
}

void GeometryController::reserve(uint8_t level, uint32_t characters) { levels_.at(level)->store.reserve(characters); }

void GeometryController::end_character(uint32_t character) {
    if (character >= level_of_.size() || level_of_[character] == kNoLevel) return;
    end_fade(character);
    end_morph_source(character);
    levels_[level_of_[character]]->store.release(slot_of_[character]);
    level_of_[character] = kNoLevel;
}

SurfaceView GeometryController::surface(uint32_t character) const {
    const uint8_t l = level_of(character);
    return l == kNoLevel ? SurfaceView{} : slot_surface(l, slot_of_[character]);
}

SurfaceView GeometryController::slot_surface(uint8_t l, uint32_t s) const {
    SurfaceView view;
    const Level& L = *levels_[l];
    view.level = l;
    view.topology_key = topology_key(l);
    if (!L.mesh_level || !L.store.valid[s]) return view;
    if (L.subdivision) {
        if (!L.keep_refined) return view;
        view.positions = L.store.refined_positions(s);
        view.normals = L.store.refined_normals(s);
    } else {
        view.positions = L.control(s);
        view.normals = L.store.normals(s);
    }
    return view;
}

std::span<const glm::mat4> GeometryController::proxy_boxes(uint32_t character) const {
    const uint8_t l = level_of(character);
    if (l == kNoLevel || levels_[l]->lod.method != GeomMethod::RigidProxy) return {};
    const uint32_t s = slot_of_[character];
    return levels_[l]->store.valid[s] ? levels_[l]->store.boxes(s) : std::span<const glm::mat4>{};
}

void GeometryController::muscle_surface(uint32_t character, std::vector<glm::vec3>& positions) const {
    positions.clear();
    const uint8_t l = level_of(character);
    if (l == kNoLevel || !levels_[l]->layered()) return;
    const Level& L = *levels_[l];
    const uint32_t s = slot_of_[character];
    if (!L.store.valid[s]) return;
    const std::span<const glm::vec3> muscles = L.store.muscle_positions(s);
    positions.assign(muscles.begin(), muscles.end());
}

void GeometryController::spring_roots(uint32_t character, std::vector<glm::vec3>& roots) const {
    roots.clear();
    const uint8_t l = level_of(character);
    if (l == kNoLevel || !levels_[l]->layered() || levels_[l]->skin == nullptr) return;
    const Level& L = *levels_[l];
    const uint32_t s = slot_of_[character];
    if (!L.store.valid[s]) return;
    const std::span<const glm::vec3> muscles = L.store.muscle_positions(s);
    roots.reserve(L.skin->bindings.size());
    for (const BlendBinding& b : L.skin->bindings) roots.push_back(blend_root(muscles, L.theta_steps, L.phi_steps, b));
}

std::span<const uint32_t> GeometryController::level_indices(uint8_t level) const { return levels_.at(level)->indices; }

std::span<const glm::vec2> GeometryController::level_uvs(uint8_t level) const { return levels_.at(level)->uvs; }

std::span<const glm::vec4> GeometryController::level_colours(uint8_t level) const { return levels_.at(level)->colours; }

std::span<const uint16_t> GeometryController::level_vertex_materials(uint8_t level) const {
    return levels_.at(level)->vertex_material;
}

uint32_t GeometryController::topology_key(uint8_t level) const {
    const Level& L = *levels_.at(level);
    return uint32_t{geometry_->type()} << 16 | uint32_t{L.revision} << 8 | level;
}

const GeomLod& GeometryController::level(uint8_t level) const { return levels_.at(level)->lod; }

uint32_t GeometryController::vertices_per_character(uint8_t level) const { return levels_.at(level)->display_vertices; }

size_t GeometryController::bytes_per_character(uint8_t level) const { return levels_.at(level)->store.bytes_per_slot(); }

uint32_t GeometryController::slot_capacity(uint8_t level) const { return levels_.at(level)->store.capacity(); }

uint32_t GeometryController::slots_per_page(uint8_t level) const { return levels_.at(level)->store.slots_per_page(); }

uint32_t GeometryController::characters_at(uint8_t level) const { return levels_.at(level)->store.in_use(); }

size_t GeometryController::memory_bytes() const {
    size_t bytes = level_of_.size() * (sizeof(uint8_t) + sizeof(uint32_t));
    for (const auto& L : levels_)
        bytes += L->store.allocated_bytes();
    return bytes;
}

GeometryWork GeometryController::work(uint8_t level) const {
    const Level& L = *levels_.at(level);
    return {L.work_characters.load(std::memory_order_relaxed), L.work_springs.load(std::memory_order_relaxed),
            L.work_vertices.load(std::memory_order_relaxed)};
}

void GeometryController::reset_work() {
    for (const auto& L : levels_) {
        L->work_characters.store(0, std::memory_order_relaxed);
        L->work_springs.store(0, std::memory_order_relaxed);
        L->work_vertices.store(0, std::memory_order_relaxed);
    }
}

uint8_t GeometryController::level_of(uint32_t character) const {
    return character < level_of_.size() ? level_of_[character] : kNoLevel;
}

uint16_t GeometryController::geomorph_frames_left(uint32_t character) const {
    const uint8_t l = level_of(character);
    if (l == kNoLevel) return 0;
    return levels_[l]->store.frames_left_of(slot_of_[character]);
}

}  // namespace aloha
