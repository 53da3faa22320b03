// The geometric controller's part of a frame, over spans: level switches marshalled from the LOD
// resolver to each type's controller, then the muscle and skin stages run per (type, level) range.
// World's systems and a game with its own entity store call these same functions.
#pragma once

#include "components/character.hpp"
#include "components/lod.hpp"
#include "components/motion.hpp"
#include "components/transform.hpp"
#include "systems/frame/level_groups.hpp"
#include "systems/geometry/controller/geometry_controller.hpp"

#include <cstdint>
#include <functional>
#include <span>
#include <string>
#include <vector>

namespace aloha {

/// One character type's geometric controller and where its characters' pose matrices live.
struct GeometryType {
    GeometryController* controller = nullptr;
    PoseSource poses;
};

/// Runs fn(begin, end) over chunks of [0, count) of `grain` elements, possibly in parallel
/// (a scheduler's parallel_for). Empty: serial.
using GeometryChunkRunner = std::function<void(size_t count, size_t grain, const std::function<void(size_t, size_t)>& fn)>;

/// Tells each character's controller about the geometric level the resolver chose: first every
/// controller's cross-fades advance a frame (GeometryController::advance_fades; call this once per frame);
/// on the first frame every element enters its level (no morph); later, the elements listed in `changed`
/// (the resolver's changed_indices, elements) whose geometric level moved begin it, geomorphing from the
/// previous surface over transition_frames(geom.geomorph_s, dt) frames, and cross-fading into or out of an
/// impostor level, or between mesh levels showing different surfaces (LevelFade), over transition_frames of
/// the longer of the left and entered levels' geomorph_s. types[refs[e].type] must exist.
void apply_level_switches(std::span<const GeometryType> types, std::span<const CharacterRef> refs,
                          std::span<const LodState> states, std::span<const GeomLod> geom,
                          std::span<const uint32_t> changed, bool first_frame, float dt);

/// The muscle and skin stages for every (type, level) range of `groups`.
struct GeometryUpdateJob {
    std::span<const GeometryType> types;   ///< by CharacterRef::type
    const CharacterGroups* groups = nullptr;  ///< grouping of this frame's levels (group_by_level)
    std::span<const LodState> states;      ///< per element
    std::span<const MotionState> motion;   ///< per element (frames_since_update: who was posed)
    std::span<const Transform> placements; ///< per element: world placement this frame, after motion (the
                                           ///< fat springs feel the root's motion; fat_spring_frame.hpp)
    float dt = 0.0f;                       ///< seconds this frame advances (fat springs)
    bool first_frame = false;              ///< every character needs its surface built
    std::span<uint64_t> level_ns{};        ///< optional: per geometric level, ns added (budget learning)
    GeometryChunkRunner run_chunks{};      ///< optional: who runs the chunks (default: serial)
    std::vector<uint32_t>* scratch = nullptr;  ///< required by RunSkin: reused id list

    /// True when the job can run; appends one message per failure to `errors` when given.
    bool Validate(std::vector<std::string>* errors = nullptr) const;
    /// Muscle stage: per range of a Layered or Subdivided level (as the type draws it) shapes and
    /// tessellates the muscles for the pose. Requires Validate().
    void RunMuscles() const;
    /// Skin stage: per range of a drawn level, the level's skin. Proxies and linear-blend skins depend
    /// on the pose alone, so only characters posed this frame, entering the level or morphing are
    /// updated; richer levels run every frame (the fat springs move). Then, serially, the surfaces of the
    /// levels being cross-faded out of into an impostor or another mesh level (GeometryController::update_fades;
    /// their poses must be read every frame: PoseUse::EveryFrame). Requires Validate().
    void RunSkin() const;
};

}  // namespace aloha
