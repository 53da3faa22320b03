// GeometryController: runs the geometric LOD levels of one character type for a crowd.
//
// Each level (a GeomLod of the rule file, level 0 = richest) owns a SlotStore; a character holds one
// slot of the level it is in. Methods:
//   RigidProxy  -> RigidProxyJob: one box per joint, matrices map the cube [-1, 1]^3 onto the box
//                  (character space).
//   SkinnedMesh -> LinearBlendSkinJob of the real mesh, or of the generated continuous skin at the
//                  level's (T, P) (a type without a mesh; skin_layer.hpp).
//   Layered     -> MuscleShapeJob + MuscleTessellateJob, then BlendSpringJob: every skin vertex (of
//                  the generated skin at (T, P), or of the real mesh) is the outer end of a fat spring
//                  rooted at a blend of several muscles' surface points (blend_binding.hpp); without
//                  the fat layer (GeomLod::layers) the skin sits at the springs' rest ends. Normals
//                  from the triangles.
//   Subdivided  -> Layered, then SubdivideJob at GeomLod::subdiv_level (the control surface is the
//                  Layered skin; its normals are not computed).
// The "control surface" of a mesh level is its skin layer's vertices; the displayed surface is the
// control surface, refined at Subdivided levels. A switch morphs the displayed surfaces: two levels
// showing the same surface (a real mesh, or the same (T, P), both refined alike) vertex by vertex;
// otherwise the old displayed surface is read at the new displayed vertices through
// CharacterGeometry::surface_map (closest points at rest). GeomorphJob slides the new surface from
// it over N frames, at a Subdivided level after refinement (morph after refinement: the first frame
// lies on what was shown, Catmull-Clark's shrinkage of the control hull included). A Subdivided
// level whose refined surfaces are not kept does not morph. The correspondences between neighbouring
// mesh levels of the table are built with the levels (set_levels), others at their first switch.
// Threading: begin_level / end_character / set_levels are serial (between frames or in the resolve
// phase). update() may run concurrently for DISJOINT character lists of the same or different
// levels: it only writes the slots of its characters and allocates nothing.
#pragma once

#include "components/lod.hpp"
#include "components/transform.hpp"
#include "systems/geometry/controller/character_geometry.hpp"
#include "systems/geometry/controller/slot_store.hpp"
#include "systems/geometry/spring_skin/fat_spring.hpp"

#include <glm/glm.hpp>

#include <cstdint>
#include <memory>
#include <span>
#include <vector>

namespace aloha {

/// Where the model-space (character space) joint matrices of every character live: character c's
/// joint_count matrices start at model + c * stride. Requires stride >= the type's joint count.
struct PoseSource {
    const glm::mat4* model = nullptr;  ///< matrices of character 0
    size_t stride = 0;                 ///< matrices between consecutive character ids
    /// The `count` matrices of character `c`.
    [[nodiscard]] std::span<const glm::mat4> joints(uint32_t c, size_t count) const {
        return {model + size_t{c} * stride, count};
    }
};

/// Where the world placements of the characters handed to update_skin live: characters[i]'s is
/// transforms[elements[i]] (elements parallel to the character list). Empty: every character stays
/// where it is (model space is world space for its fat springs).
struct PlacementSource {
    std::span<const Transform> transforms;  ///< the host's placements (per element)
    std::span<const uint32_t> elements;     ///< per character handed to update_skin: its element
};

/// Work a level's update_skin() calls have done since the last GeometryController::reset_work()
/// (counted per character updated; for `aloha profile` and tests of layer peeling).
struct GeometryWork {
    uint64_t characters = 0;       ///< characters whose skin stage ran
    uint64_t springs_stepped = 0;  ///< fat springs updated (one per skin vertex at levels with the fat layer)
    uint64_t skin_vertices = 0;    ///< control-surface vertices placed (LBS, or muscle-blended rest ends / spring ends)
};

/// One character's current mesh surface (character space). Empty spans for RigidProxy / Hidden /
/// no level / not yet updated.
struct SurfaceView {
    uint8_t level = 0xFF;                 ///< geometric level, 0xFF = none
    uint32_t topology_key = 0;            ///< type << 16 | revision << 8 | level: same key, same index buffer
    std::span<const glm::vec3> positions; ///< vertices (grid layout, mesh order or refined)
    std::span<const glm::vec3> normals;   ///< unit normals, same size
};

/// Whether level `lod` is drawn lit per vertex: the skinned level, for characters small on screen
/// (docs/PERFORMANCE.md), unless it stands in for a richer level (GeomLod::lit_per_pixel); the others are lit per
/// pixel. The renderer's topology and the mesh cross-fades use it.
[[nodiscard]] inline bool drawn_lit_per_vertex(const GeomLod& lod) { return lod.method == GeomMethod::SkinnedMesh && !lod.lit_per_pixel; }

/// True for the methods drawn as a deformed mesh over a registered topology (skinned, layered, subdivided).
[[nodiscard]] inline bool drawn_as_mesh(GeomMethod m) {
    return m == GeomMethod::SkinnedMesh || m == GeomMethod::Layered || m == GeomMethod::Subdivided;
}

/// A cross-fade between two levels, begun by GeometryController::begin_level for a switch of N >= 2 fade frames
/// either way (apply_level_switches: the longer of the two levels' geomorph_s, so impostor <-> rigid proxy fades
/// too): between an `impostor` level and a drawn level (rigid proxy or mesh), or between two mesh levels whose
/// displayed surfaces differ (topology, or vertex- against pixel-lighting: skinned <-> layered / subdivided, two
/// layered resolutions). The switch frame and the N - 2 after it show the character at both levels with
/// complementary screen-door dithers (frame k = 1 .. N - 1 of the switch gives the entered level k / N of the
/// pixels, as a geomorph's frame k is k / N of the way), frame N the entered level alone. Leaving a drawn level
/// for the impostor, or a mesh level for another, keeps the left level's slot meanwhile (update_fades keeps it
/// posed); entering a drawn level from the impostor needs nothing kept.
struct LevelFade {
    static constexpr uint32_t kNoSlot = 0xFFFFFFFFu;  ///< kept_slot of a fade out of the impostor level
    uint32_t character = 0;       ///< the character (id in its type)
    uint8_t from_level = 0;       ///< the level it left
    bool between_meshes = false;  ///< both levels are mesh levels (the left one kept; no impostor drawn)
    uint16_t frames_total = 0;    ///< N, the switch's fade frames (>= 2)
    uint16_t frames_left = 0;     ///< frames after this one that still show both (N - k on frame k), >= 1
    uint32_t kept_slot = kNoSlot; ///< the left level's slot, kept while fading into the impostor or another mesh level

    /// True when the character is entering the impostor level (the drawn level is the one left).
    [[nodiscard]] bool into_impostor() const { return kept_slot != kNoSlot && !between_meshes; }
    /// True when the left level's slot is kept (and posed by update_fades) during the fade.
    [[nodiscard]] bool keeps_left() const { return kept_slot != kNoSlot; }
    /// Share of the character's pixels the drawn (proxy or mesh) side shows this frame, in (0, 1); the
    /// impostor shows the rest (gpu::lit_dither_bits, ImpostorInstance::forward_phase.w = -share). Between
    /// meshes, the entered level's share; the left level shows the rest (DeformableMesh::dither = -share).
    [[nodiscard]] float drawn_share() const {
        const uint16_t entered = static_cast<uint16_t>(frames_total - frames_left);  // k: frames of the new level's share
        return static_cast<float>(into_impostor() ? frames_left : entered) / static_cast<float>(frames_total);
    }
};

/// The geometric controller of one character type.
class GeometryController {
public:
    /// "No level" marker for level_of().
    static constexpr uint8_t kNoLevel = 0xFF;

    /// Controller for `geometry` (must outlive it) with the rule file's levels (at most 255; each
    /// grid level needs T >= 3, P >= 2; subdiv_level <= 4) and room for `capacity` character ids
    /// (grows when a larger id enters). Builds every level's shared data (tables, bind meshes,
    /// subdivision, index buffers). `keep_refined_surfaces` false: Subdivided levels still refine
    /// every frame but into per-thread scratch, keeping no refined surface per character (for runs
    /// with no renderer; surface() is then empty at those levels), which takes their memory per
    /// character from ~3.5 MB to ~1.6 MB at 24x16.
    GeometryController(const CharacterGeometry& geometry, std::span<const GeomLod> levels, uint32_t capacity,
                       bool keep_refined_surfaces = true);
    ~GeometryController();
    GeometryController(const GeometryController&) = delete;
    GeometryController& operator=(const GeometryController&) = delete;

    /// Replaces the level table (rule reload). Levels whose method, (T, P) and subdivision are
    /// unchanged keep their storage and characters; changed levels are rebuilt (new topology key)
    /// and their characters get fresh slots (springs restart at rest, no morph). Characters in a
    /// level past the new table's end move to its last level. Serial only.
    void set_levels(std::span<const GeomLod> levels);

    /// `character` enters `level`: takes a slot there, starts a geomorph of `geomorph_frames` frames
    /// from its old surface when both levels are mesh levels, the old surface has been shown and they are not two
    /// SkinnedMesh levels over the same vertices (which place them alike: nothing to morph), and releases the old
    /// slot; a geomorph keeps it instead until the next advance_fades (posed by update_fades, it gives the morph
    /// its start at the frame's pose) unless a cross-fade keeps it. A switch into or out of an impostor level from or to a drawn level
    /// cross-fades instead (LevelFade) over `fade_frames` frames when that is 2 or more; so does a switch
    /// between mesh levels whose displayed surfaces differ, the old one shown (geomorph kept as well). `previous_level`
    /// is the caller's view of the old level (-1 on spawn); the controller's own record wins when they
    /// differ. Entering the current level again does nothing. Serial only. Requires level < level_count().
    void begin_level(uint32_t character, uint8_t level, int8_t previous_level, uint16_t geomorph_frames, uint16_t fade_frames);
    /// The same with a cross-fade as long as the geomorph (fade_frames = geomorph_frames).
    void begin_level(uint32_t character, uint8_t level, int8_t previous_level, uint16_t geomorph_frames) {
        begin_level(character, level, previous_level, geomorph_frames, geomorph_frames);
    }
    /// Ends the frame's cross-fades: every LevelFade advances one frame, and those at their last frame end
    /// (their kept slots released); the left levels' slots kept only for a geomorph's start (begin_level) are
    /// released. Call once per frame before the frame's begin_level calls (apply_level_switches does). Serial only.
    void advance_fades();
    /// The cross-fade `character` is in, or nullptr (see LevelFade).
    [[nodiscard]] const LevelFade* fade(uint32_t character) const {
        return character < fade_index_.size() && fade_index_[character] != LevelFade::kNoSlot ? &fades_[fade_index_[character]] : nullptr;
    }
    /// Every running cross-fade (order unspecified but deterministic).
    [[nodiscard]] std::span<const LevelFade> fades() const { return fades_; }
    /// The kept slots of fades into the impostor level or between meshes, and of geomorphs without a fade: the
    /// left level's surface (or proxy boxes) for each character's pose in `poses` this frame, as update_muscles +
    /// update_skin would (fat springs not carried with the placement). Serial; the `spring_skin` stage's
    /// (GeometryUpdateJob::RunSkin) first step: run before update_skin, an entered mesh level starts its geomorph
    /// from the kept surface at this frame's pose (else from the one shown at the switch).
    void update_fades(const PoseSource& poses, float dt);
    /// The surface `character` shows at the level it is fading out of (a LevelFade from a mesh level into the
    /// impostor level or another mesh level), as surface() would there; empty otherwise.
    [[nodiscard]] SurfaceView fade_surface(uint32_t character) const;
    /// The proxy boxes of a character fading from a RigidProxy level into the impostor level; empty otherwise.
    [[nodiscard]] std::span<const glm::mat4> fade_proxy_boxes(uint32_t character) const;

    /// Allocates room for `characters` characters at `level` at once (no-op when there is room), for a
    /// caller that knows they will all enter it. Serial only. Requires level < level_count().
    void reserve(uint8_t level, uint32_t characters);
    /// Releases the character's slot (despawn). Serial only.
    void end_character(uint32_t character);

    /// The `muscle` stage (Tessellate phase) of `level`'s method for `characters` (each must
    /// currently be in `level`): shapes the muscles for their poses in `poses` (volume kept) and
    /// tessellates them at the level's (T, P) into each character's muscle surface. Does nothing at
    /// levels without muscles. Thread-safe for disjoint character lists.
    void update_muscles(uint8_t level, std::span<const uint32_t> characters, const PoseSource& poses);
    /// The `spring_skin` stage (Skin phase): rigid proxies and linear-blend skins from the poses;
    /// at muscle levels fat springs (frame time `dt` > 0) on the muscle surface update_muscles wrote
    /// this frame, the skin, geomorph and OpenSubdiv refinement. A geomorph starts, on the entered level's first update,
    /// from the left level's kept slot (a cross-fade's, or the morph's own) as update_fades last posed it (the
    /// surface shown at the switch when it has not run since); dropped when advance_fades released that slot first.
    /// Thread-safe for disjoint lists.
    void update_skin(uint8_t level, std::span<const uint32_t> characters, const PoseSource& poses, float dt);
    /// The same with the characters' world placements this frame: the fat springs feel the root's
    /// motion (start, stop, turn, landing; fat_spring_frame.hpp), a teleport or snap excepted.
    void update_skin(uint8_t level, std::span<const uint32_t> characters, const PoseSource& poses, float dt,
                     const PlacementSource& placements);
    /// Both stages, one after the other (update_muscles then update_skin).
    void update(uint8_t level, std::span<const uint32_t> characters, const PoseSource& poses, float dt,
                const PlacementSource& placements = {});

    /// The character's displayed surface (valid until its next update / begin_level / set_levels);
    /// positions and normals are empty before its first update, at levels with no mesh, and at
    /// Subdivided levels when refined surfaces are not kept.
    [[nodiscard]] SurfaceView surface(uint32_t character) const;
    /// The character's proxy boxes (one per joint, unit cube [-1, 1]^3 -> box, character space), or
    /// empty when it is not at a RigidProxy level.
    [[nodiscard]] std::span<const glm::mat4> proxy_boxes(uint32_t character) const;
    /// Copies the character's tessellated muscle surface as of its last update (muscles x V(T, P),
    /// for debug drawing) to `positions`, or clears it when its level has no muscles or it has not
    /// been updated. Allocates.
    void muscle_surface(uint32_t character, std::vector<glm::vec3>& positions) const;
    /// Copies the roots of the character's fat springs as of its last update (one per displayed
    /// control vertex: the blend of muscle-surface points each skin vertex hangs on) to `roots`, or
    /// clears it when its level has no muscles or it has not been updated. For debug drawing; allocates.
    void spring_roots(uint32_t character, std::vector<glm::vec3>& roots) const;
    /// Triangle list shared by every character of `level` (empty for RigidProxy / Hidden).
    [[nodiscard]] std::span<const uint32_t> level_indices(uint8_t level) const;
    /// Texture coordinates of `level`'s displayed vertices, shared by every character there: the real
    /// mesh's (stencil-interpolated when subdivided), or the generated body UVs of the grid skin
    /// (body_texture.hpp); empty for RigidProxy / Hidden and for a real mesh without UVs.
    [[nodiscard]] std::span<const glm::vec2> level_uvs(uint8_t level) const;
    /// Material index (into the type's materials) of each displayed vertex of `level`; empty = all 0.
    [[nodiscard]] std::span<const uint16_t> level_vertex_materials(uint8_t level) const;
    /// LINEAR colour of each displayed vertex of `level` (the real mesh's COLOR_0, stencil-interpolated when
    /// subdivided); empty = white.
    [[nodiscard]] std::span<const glm::vec4> level_colours(uint8_t level) const;
    /// Topology key of `level` (see SurfaceView::topology_key).
    [[nodiscard]] uint32_t topology_key(uint8_t level) const;

    /// Number of levels.
    [[nodiscard]] uint8_t level_count() const { return static_cast<uint8_t>(levels_.size()); }
    /// The level's parameters.
    [[nodiscard]] const GeomLod& level(uint8_t level) const;
    /// Displayed vertices per character at `level` (0 for RigidProxy / Hidden).
    [[nodiscard]] uint32_t vertices_per_character(uint8_t level) const;
    /// Bytes of per-character storage at `level` (what one character costs there).
    [[nodiscard]] size_t bytes_per_character(uint8_t level) const;
    /// Slots allocated at `level` (grows by one page only when all are in use).
    [[nodiscard]] uint32_t slot_capacity(uint8_t level) const;
    /// Slots per page of `level`'s storage (capacity grows in these steps).
    [[nodiscard]] uint32_t slots_per_page(uint8_t level) const;
    /// Slots in use at `level`: its characters, plus the slots kept there by cross-fades out of it and by
    /// reference springs (step_reference_springs).
    [[nodiscard]] uint32_t characters_at(uint8_t level) const;
    /// Bytes of all per-character storage (with a spare page prepared in the background) plus the
    /// shared index buffers.
    [[nodiscard]] size_t memory_bytes() const;
    /// The character's level, or kNoLevel.
    [[nodiscard]] uint8_t level_of(uint32_t character) const;
    /// Geomorph frames the character still has to show (0 when not morphing).
    [[nodiscard]] uint16_t geomorph_frames_left(uint32_t character) const;
    /// Character ids the controller has room for.
    [[nodiscard]] uint32_t capacity() const { return static_cast<uint32_t>(level_of_.size()); }
    /// The character type.
    [[nodiscard]] const CharacterGeometry& geometry() const { return *geometry_; }

    /// Work done at `level` since the last reset_work() (thread-safe counters, summed over update calls).
    [[nodiscard]] GeometryWork work(uint8_t level) const;
    /// Zeroes every level's work counters. Serial only.
    void reset_work();

    /// Fat-spring tuning (dt is replaced by update's dt).
    [[nodiscard]] const FatSpringParams& spring_params() const { return spring_params_; }
    /// Sets the fat-spring tuning. Serial only.
    void set_spring_params(const FatSpringParams& params) { spring_params_ = params; }

    /// The surface `character` would have at `reference_level` for its pose in `poses`, computed
    /// without touching any state (springs at rest, no morph), strain limited as shown unless
    /// `strain_limited` is false (the fat layer's own rest ends, to compare with fat_spring_ends).
    /// Empty for RigidProxy / Hidden. Allocates (a measurement tool, not per-frame code).
    void reference_surface(const PoseSource& poses, uint32_t character, uint8_t reference_level,
                           std::vector<glm::vec3>& positions, bool strain_limited = true) const;
    /// The fat layer of `character` as its springs left it at the last update (before the skin's
    /// strain limit: what the spring dynamics alone did); empty at a level without fat springs.
    [[nodiscard]] std::span<const glm::vec3> fat_spring_ends(uint32_t character) const;
    /// Matched point pairs for fidelity: for every vertex of the character's current control surface
    /// (the displayed surface, before subdivision) `current` gets the vertex (on a level drawn with a
    /// simplified triangle list, the point of that list's surface that shows it: Level::simplified_map) and `reference` the
    /// reference level's control surface (springs at rest) at the same (muscle, theta, phi) (bilinear
    /// on the reference grid), or the same mesh vertex for a real mesh. Both are empty when either
    /// level is not a mesh level or the character has not been updated yet. `current_at_rest`, when
    /// given, gets the current level's control surface for the same pose with its springs at rest and
    /// no morph (vertex for vertex with `current`): `current - current_at_rest` is the springs' own
    /// motion and any geomorph, `current_at_rest - reference` the level's geometric error. Allocates.
    /// `reference_moving`, when given, gets the reference level's control surface with the character's
    /// reference springs as they moved (step_reference_springs), matched like `reference`: the full-detail
    /// body with its own fat motion. Empty when the character carries no reference springs at `reference_level`.
    void deviation_pairs(const PoseSource& poses, uint32_t character, uint8_t reference_level,
                         std::vector<glm::vec3>& current, std::vector<glm::vec3>& reference,
                         std::vector<glm::vec3>* current_at_rest = nullptr, std::vector<glm::vec3>* reference_moving = nullptr) const;
    /// Reference springs (fidelity; a measurement tool, serial only, allocates): each of `characters` now at a
    /// mesh level carries, beside its shown level, the fat springs of `reference_level` stepped by `dt` for
    /// its pose in `poses` and its placement `placements[i]`, started at rest on the first call that gives it
    /// (as a level's springs start when it is entered). Characters not given, or not at a mesh level, drop
    /// theirs; a call with another reference level drops all. Nothing is carried when that level has no fat
    /// springs. Requires placements.size() == characters.size().
    void step_reference_springs(uint8_t reference_level, std::span<const uint32_t> characters, const PoseSource& poses, float dt,
                                std::span<const Transform> placements);
    /// Frames the character's reference springs have been stepped since they started (0: none carried).
    [[nodiscard]] uint32_t reference_spring_frames(uint32_t character) const;

    struct Level;  ///< per-level shared data + storage (internal)

private:
    std::unique_ptr<Level> build_level(const GeomLod& lod, uint8_t index, uint8_t revision) const;
    void capture_morph(const Level& from, uint32_t from_slot, Level& to, uint32_t to_slot);
    // Reads a pending morph's start from the left level's kept slot (a cross-fade's or a morph source's), posed
    // this frame by update_fades; without one the morph is dropped.
    void start_morph(uint32_t character, Level& to, uint32_t to_slot);
    // Poses the kept `slot` of level `L` for `pose`, as its level's stages would (update_fades).
    void pose_kept_slot(Level& L, uint32_t slot, std::span<const glm::mat4> pose, const FatSpringParams& params,
                        std::span<const FatSpringParams> tunings, float dt);
    void end_morph_source(uint32_t character);  ///< releases the character's morph source slot, if any
    void end_morph_sources();                   ///< releases every morph source slot
    void control_surface(const Level& level, std::span<const glm::mat4> pose, std::vector<glm::vec3>& out,
                         bool strain_limited = true) const;
    void ensure_capacity(uint32_t character);
    [[nodiscard]] SurfaceView slot_surface(uint8_t level, uint32_t slot) const;
    [[nodiscard]] bool crossfades(uint8_t from, uint8_t to) const;
    [[nodiscard]] bool mesh_crossfades(uint8_t from, uint8_t to) const;
    void begin_fade(uint32_t character, uint8_t from, uint32_t old_slot, uint16_t frames, bool between_meshes);
    void end_fade(uint32_t character);
    void end_fades();
    void drop_reference_springs();  ///< every character's reference springs released

    const CharacterGeometry* geometry_;
    std::vector<std::unique_ptr<Level>> levels_;
    std::vector<uint8_t> level_of_;
    std::vector<uint32_t> slot_of_;
    std::vector<LevelFade> fades_;        ///< running cross-fades
    std::vector<uint32_t> fade_index_;    ///< per character: its index in fades_, LevelFade::kNoSlot when none
    // A left level's slot kept, where no cross-fade keeps it, from a switch that starts a geomorph until the next
    // advance_fades: update_fades poses it, and the entered level's first update starts its morph from it.
    struct MorphSource {
        uint32_t character = 0;
        uint8_t from_level = 0;
        uint32_t slot = 0;
    };
    std::vector<MorphSource> morph_sources_;
    FatSpringParams spring_params_;
    bool keep_refined_ = true;
    uint8_t reference_level_ = kNoLevel;          ///< the level of the reference springs (kNoLevel: none)
    std::vector<uint32_t> reference_slot_;         ///< per character: its reference springs' slot there, or LevelFade::kNoSlot
    std::vector<uint32_t> reference_frames_;       ///< per character: frames its reference springs were stepped
    std::vector<uint32_t> reference_characters_;   ///< the characters carrying reference springs
};

}  // namespace aloha
