#include "systems/frame/geometry_frame.hpp"

#include "systems/lod/resolver.hpp"

#include <algorithm>
#include <chrono>

namespace aloha {

namespace {

uint64_t now_ns() {
    return static_cast<uint64_t>(
        std::chrono::duration_cast<std::chrono::nanoseconds>(std::chrono::steady_clock::now().time_since_epoch()).count());
}

// Runs `fn` over [0, count) in chunks of `grain` with `run` (serial when empty), timing it into `level_ns`.
void run_range(const GeometryChunkRunner& run, size_t count, size_t grain, std::span<uint64_t> level_ns, uint8_t level,
               const std::function<void(size_t, size_t)>& fn) {
    const uint64_t start = now_ns();
    if (run) run(count, grain, fn);
    else if (count > 0) fn(0, count);
    if (level < level_ns.size()) level_ns[level] += now_ns() - start;
}

}  // namespace

void apply_level_switches(std::span<const GeometryType> types, std::span<const CharacterRef> refs,
                          std::span<const LodState> states, std::span<const GeomLod> geom,
                          std::span<const uint32_t> changed, bool first_frame, float dt) {
    for (const GeometryType& t : types)  // last frame's cross-fades move on (or end) before this frame's switches
        if (t.controller) t.controller->advance_fades();
    if (first_frame) {
        for (size_t e = 0; e < refs.size(); ++e) types[refs[e].type].controller->begin_level(refs[e].id, states[e].geom_level, -1, 0);
        return;
    }
    for (const uint32_t e : changed) {
        GeometryController& gc = *types[refs[e].type].controller;
        const uint8_t old = gc.level_of(refs[e].id);
        if (old == states[e].geom_level) continue;  // animation level only
        // A geomorph takes the entered level's time; a cross-fade (impostor <-> drawn level, mesh <-> mesh) shows both levels
        // and hides the same difference whichever way the switch goes, so it takes the longer of the two
        // levels' times: a rigid proxy (geomorph_s 0: no surface to morph) fades with the impostor's.
        const float left_s = old == GeometryController::kNoLevel ? 0.0f : gc.level(old).geomorph_s;
        gc.begin_level(refs[e].id, states[e].geom_level, static_cast<int8_t>(states[e].prev_geom_level),
                       transition_frames(geom[e].geomorph_s, dt), transition_frames(std::max(geom[e].geomorph_s, left_s), dt));
    }
}

bool GeometryUpdateJob::Validate(std::vector<std::string>* errors) const {
    bool ok = true;
    auto fail = [&](const std::string& m) {
        ok = false;
        if (errors) errors->push_back("GeometryUpdateJob: " + m);
    };
    if (!groups) return fail("groups is null"), false;
    if (states.size() != groups->size() || motion.size() != groups->size() || placements.size() != groups->size())
        fail("states, motion and placements need one element per grouped character");
    if (!scratch) fail("scratch is null");
    for (const LevelRange& r : groups->ranges)
        if (r.type >= types.size() || !types[r.type].controller) {
            fail("no geometric controller for type " + std::to_string(r.type));
            break;
        }
    return ok;
}

void GeometryUpdateJob::RunMuscles() const {
    for (const LevelRange& r : groups->ranges) {
        const GeometryType& t = types[r.type];
        const GeomMethod method = t.controller->level(r.level).method;  // as the type draws it
        if (method != GeomMethod::Layered && method != GeomMethod::Subdivided) continue;
        const std::span<const uint32_t> ids(groups->ids.data() + r.begin, r.end - r.begin);
        run_range(run_chunks, ids.size(), 1, level_ns, r.level,
                  [&](size_t b, size_t e) { t.controller->update_muscles(r.level, ids.subspan(b, e - b), t.poses); });
    }
}

void GeometryUpdateJob::RunSkin() const {
    // Characters fading into the impostor level or another mesh level: the level they left, still drawn (a few
    // per switch frame), posed first so that a level entered from another mesh level starts its geomorph from
    // the left one's surface at this frame's pose.
    for (const GeometryType& t : types)
        if (t.controller) t.controller->update_fades(t.poses, dt);
    scratch->resize(groups->size());
    for (const LevelRange& r : groups->ranges) {
        const GeometryType& t = types[r.type];
        const GeomMethod method = t.controller->level(r.level).method;  // as the type draws it
        if (method == GeomMethod::Hidden) continue;
        std::span<const uint32_t> ids(groups->ids.data() + r.begin, r.end - r.begin);
        if (method == GeomMethod::RigidProxy || method == GeomMethod::SkinnedMesh) {
            size_t n = 0;
            for (uint32_t p = r.begin; p < r.end; ++p) {
                const uint32_t e = groups->order[p];
                if (motion[e].frames_since_update == 0 || states[e].seconds_at_geom == 0.0f || states[e].geomorph_left_s > 0.0f ||
                    first_frame || t.controller->geomorph_frames_left(groups->ids[p]) > 0)
                    (*scratch)[r.begin + n++] = groups->ids[p];
            }
            ids = std::span<const uint32_t>(scratch->data() + r.begin, n);
        }
        // Grain: cheap methods in big chunks, rich ones one or a few characters each. An impostor has no skin to
        // place (only its slot is marked), so its whole range is a few calls, not one per character: per call the
        // controller adds to shared work counters, which two threads calling it per character fight over.
        const size_t grain = method == GeomMethod::Impostor     ? 4096
                             : method == GeomMethod::RigidProxy  ? 256
                             : method == GeomMethod::SkinnedMesh ? 16
                                                                 : 1;
        // Layered levels take the whole range, so their elements are the grouping's order at the same positions.
        const bool whole = method == GeomMethod::Layered || method == GeomMethod::Subdivided;
        const std::span<const uint32_t> elements(groups->order.data() + r.begin, r.end - r.begin);
        run_range(run_chunks, ids.size(), grain, level_ns, r.level, [&](size_t b, size_t e) {
            const PlacementSource placed = whole ? PlacementSource{placements, elements.subspan(b, e - b)} : PlacementSource{};
            t.controller->update_skin(r.level, ids.subspan(b, e - b), t.poses, dt, placed);
        });
    }
}

}  // namespace aloha
