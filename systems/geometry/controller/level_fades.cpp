// GeometryController's cross-fades between the impostor level and a drawn level, and between two mesh levels
// whose displayed surfaces differ (LevelFade): their bookkeeping across frames and the surfaces of the levels being left;
// and the left levels' slots kept one frame as a geomorph's start where no fade keeps them (morph sources). The per-frame
// update of the kept slots is with the other stages (controller_update.cpp).
#include "systems/geometry/controller/controller_level.hpp"

#include <cassert>

namespace aloha {
namespace {

// A level a cross-fade can have on its drawn side: one with per-character geometry that is drawn.
bool drawn_method(GeomMethod m) {
    return m == GeomMethod::RigidProxy || m == GeomMethod::SkinnedMesh || m == GeomMethod::Layered || m == GeomMethod::Subdivided;
}

}  // namespace

bool GeometryController::crossfades(uint8_t from, uint8_t to) const {
    const GeomMethod a = levels_[from]->lod.method, b = levels_[to]->lod.method;
    return (a == GeomMethod::Impostor && drawn_method(b)) || (drawn_method(a) && b == GeomMethod::Impostor) || mesh_crossfades(from, to);
}

bool GeometryController::mesh_crossfades(uint8_t from, uint8_t to) const {
    // A geomorph slides the positions from the old surface, but a different displayed surface brings other
    // triangles (texture, silhouette) and a skinned level is lit per vertex, the others per pixel: both
    // change at once on the switch frame, so these switches cross-fade too (the geomorph still runs).
    const Level& a = *levels_[from];
    const Level& b = *levels_[to];
    return a.mesh_level && b.mesh_level &&
           (!(a.display_key == b.display_key) || drawn_lit_per_vertex(a.lod) != drawn_lit_per_vertex(b.lod));
}

void GeometryController::begin_fade(uint32_t character, uint8_t from, uint32_t old_slot, uint16_t frames, bool between_meshes) {
    assert(frames >= 2 && fade_index_[character] == LevelFade::kNoSlot);
    LevelFade f;
    f.character = character;
    f.from_level = from;
    f.between_meshes = between_meshes;
    f.frames_total = frames;
    f.frames_left = static_cast<uint16_t>(frames - 1);  // the switch frame is frame 1 of N
    f.kept_slot = old_slot;
    fade_index_[character] = static_cast<uint32_t>(fades_.size());
    fades_.push_back(f);
}

void GeometryController::end_fade(uint32_t character) {
    if (character >= fade_index_.size() || fade_index_[character] == LevelFade::kNoSlot) return;
    const uint32_t i = fade_index_[character];
    const LevelFade& f = fades_[i];
    if (f.kept_slot != LevelFade::kNoSlot) levels_[f.from_level]->store.release(f.kept_slot);
    fade_index_[character] = LevelFade::kNoSlot;
    if (i + 1 != fades_.size()) {  // the last fade takes the ended one's place
        fades_[i] = fades_.back();
        fade_index_[fades_[i].character] = i;
    }
    fades_.pop_back();
}

void GeometryController::end_fades() {
    while (!fades_.empty()) end_fade(fades_.back().character);
}

void GeometryController::end_morph_source(uint32_t character) {
    for (size_t i = 0; i < morph_sources_.size(); ++i) {
        if (morph_sources_[i].character != character) continue;
        levels_[morph_sources_[i].from_level]->store.release(morph_sources_[i].slot);
        morph_sources_[i] = morph_sources_.back();
        morph_sources_.pop_back();
        return;
    }
}

void GeometryController::end_morph_sources() {
    for (const MorphSource& m : morph_sources_) levels_[m.from_level]->store.release(m.slot);
    morph_sources_.clear();
}

void GeometryController::advance_fades() {
    end_morph_sources();  // last frame's switches have started their morphs
    for (size_t i = 0; i < fades_.size();) {
        LevelFade& f = fades_[i];
        if (--f.frames_left > 0) {
            ++i;
            continue;
        }
        end_fade(f.character);  // moves the last fade to i, which is looked at next
    }
}

SurfaceView GeometryController::fade_surface(uint32_t character) const {
    const LevelFade* f = fade(character);
    return f && f->keeps_left() ? slot_surface(f->from_level, f->kept_slot) : SurfaceView{};
}

std::span<const glm::mat4> GeometryController::fade_proxy_boxes(uint32_t character) const {
    const LevelFade* f = fade(character);
    if (!f || !f->into_impostor()) return {};
    const Level& L = *levels_[f->from_level];
    if (L.lod.method != GeomMethod::RigidProxy || !L.store.valid[f->kept_slot]) return {};
    return L.store.boxes(f->kept_slot);
}

}  // namespace aloha
