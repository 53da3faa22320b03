// Draw-list gathering over spans: every drawn character of a frame as renderer items in world space
// (rigid proxy boxes, deformable meshes over registered topologies, debug overlay lines), walking the
// (type, level) groups. The builder keeps the topology cache: each (type, level) index buffer and the
// type's textures and materials are registered with the renderer once, on first use.
#pragma once

#include "components/character.hpp"
#include "components/lod.hpp"
#include "components/motion.hpp"
#include "components/transform.hpp"
#include "engine/assets/surface_material.hpp"
#include "engine/core/result.hpp"
#include "systems/frame/level_groups.hpp"
#include "systems/geometry/controller/geometry_controller.hpp"
#include "systems/render/crowd_renderer.hpp"

#include <cstdint>
#include <span>
#include <string>
#include <vector>
#include <utility>
#include <string>
#include <vector>

namespace aloha {

/// Debug overlays drawn as lines over the characters (bits, combine with |).
enum OverlayBits : uint8_t { kOverlayBones = 1u << 0, kOverlayMuscles = 1u << 1, kOverlaySprings = 1u << 2 };

/// The draw lists one frame produces, in world space, ready for the renderer.
struct RenderLists {
    std::vector<DeformableMesh> meshes;
    std::vector<ProxyInstance> proxies;
    std::vector<LineSegment> lines;
    std::vector<ImpostorInstance> impostors;
    std::vector<ProxyFade> proxy_fades;  ///< runs of `proxies` drawn dithered (fading characters' boxes, at the end)
    uint32_t drawn_twice = 0;             ///< characters drawn twice (impostor + proxy or mesh, or two meshes) in a cross-fade
};

/// What the draw lists need of one character type.
struct DrawType {
    const GeometryController* geometry = nullptr;   ///< required
    PoseSource poses;                               ///< pose matrices (bone overlay)
    std::span<const int16_t> parents;               ///< skeleton parents (bone overlay)
    std::span<const uint16_t> proxy_joints;         ///< joints drawn as proxy boxes
    std::span<const SurfaceMaterial> materials;     ///< the type's surface materials (may be empty)
    std::span<const TextureImage> textures;         ///< their textures
};

/// How the characters are coloured and which overlays are drawn.
struct DrawSettings {
    DebugColour colour = DebugColour::Shaded;
    uint8_t overlay = 0;  ///< OverlayBits; with any set, skins are left out so the inner layers show
};

/// The frame's draw lists and the renderer ids they refer to. One per renderer.
class DrawListBuilder {
public:
    /// Forgets every registered topology and material id (a new renderer, or levels whose topologies
    /// changed); the impostor atlases stay (clear_impostors()).
    void reset();
    /// Forgets the impostor atlases (a new renderer): impostor levels draw nothing until set_impostor().
    void clear_impostors() { impostors_.clear(); }
    /// Draws type `type`'s impostor levels with atlas `atlas` (a renderer id), whose walk rows follow a
    /// cycle of `cycle_s` seconds of clip time (the phase of a clip-playback walk is time / cycle_s), its
    /// pictures drawn `scale` times as large as baked (an atlas baked for a type this one is a scaled copy of,
    /// impostor_share_between; > 0).
    void set_impostor(uint16_t type, uint32_t atlas, float cycle_s, float scale = 1.0f);
    /// Names the GPU pass each geometric level's meshes are drawn in (index: level; e.g. the rule file's
    /// level names); levels without a name are drawn in the pass "meshes". Takes effect for topologies
    /// registered after the call (call reset() first to relabel registered ones).
    void set_pass_names(std::vector<std::string> names) { pass_names_ = std::move(names); }
    /// Clears `out` and fills it with the characters of `groups` (positions walk elements of the spans).
    /// Proxies need no renderer; meshes need `renderer` for their topology ids (skipped when null).
    /// Impostors need their type's atlas (set_impostor) and take their walk phase from `motion` (per
    /// element; empty: phase 0); a character that is not walking shows the standing row. A character in
    /// a cross-fade (GeometryController::fade, LevelFade) with an impostor atlas for its type is drawn
    /// both as its impostor and at its drawn level (the entered one, or the one left: fade_surface /
    /// fade_proxy_boxes), with complementary dithers (DeformableMesh::dither, ProxyFade, the impostor's
    /// forward_phase.w = -share); one between two mesh levels (LevelFade::between_meshes) is drawn at both,
    /// the left level's kept surface with the complement of the entered one's dither (dither = -share);
    /// without overlays only. With `attributes` (per element; empty: every character is drawn) a character
    /// whose bounds lie wholly outside the view frustum (LodAttributes::visible == 0) is left out at any
    /// level: its level may be held there by the resolver's hysteresis, but it has no pixel to draw.
    /// Errors: the renderer refusing a topology, texture or material (the lists are then partial).
    Status gather(CrowdRenderer* renderer, std::span<const DrawType> types, const CharacterGroups& groups,
                  std::span<const Transform> transforms, std::span<const LodState> states,
                  std::span<const AnimLod> anims, const DrawSettings& settings, RenderLists& out,
                  std::span<const MotionState> motion = {}, std::span<const LodAttributes> attributes = {});
    /// Registers every type's materials and every mesh level's topology with `renderer` now (at load), so that the
    /// frame where a level first appears registers nothing (texture uploads, index lists reordered by material:
    /// 10-25 ms a type on crowd_10k, measured in render_prepare). Levels drawn as impostors, proxies or nothing, and
    /// levels without a displayed surface, are skipped. Errors: as topology().
    Status prepare(CrowdRenderer& renderer, std::span<const DrawType> types);
    /// The renderer id of `surface`'s topology for type `type`, registering it (and the type's
    /// materials) on first use.
    Result<uint32_t> topology(CrowdRenderer& renderer, uint16_t type, const DrawType& draw, const SurfaceView& surface) {
        return topology(renderer, type, draw, surface.level, surface.topology_key, static_cast<uint32_t>(surface.positions.size()));
    }
    /// The same for level `level` of type `type` (GeometryController::topology_key, `vertex_count` displayed vertices).
    Result<uint32_t> topology(CrowdRenderer& renderer, uint16_t type, const DrawType& draw, uint8_t level, uint32_t topology_key,
                              uint32_t vertex_count);
    /// True when type `type`'s materials are registered (its meshes are drawn in their colours).
    [[nodiscard]] bool textured(uint16_t type) const { return type < materials_.size() && !materials_[type].empty(); }

private:
    void overlays(const DrawType& draw, uint32_t id, const glm::mat4& world, uint8_t bits, RenderLists& out);
    /// The draw inputs of one frame's gather (spans per element).
    struct Frame {
        CrowdRenderer* renderer;
        std::span<const Transform> transforms;
        std::span<const LodState> states;
        std::span<const AnimLod> anims;
        std::span<const MotionState> motion;
        std::span<const LodAttributes> attributes;
        const DrawSettings& settings;
        /// False when element e is known to lie outside the view frustum.
        [[nodiscard]] bool in_view(uint32_t e) const { return attributes.empty() || attributes[e].visible != 0; }
    };
    Status gather_impostors(const DrawType& draw, const LevelRange& r, const CharacterGroups& groups, const Frame& f, RenderLists& out);
    /// Element e (character `id` of `type`) as its impostor, faded to show 1 - drawn_share of its pixels (1: all).
    [[nodiscard]] ImpostorInstance impostor_instance(const DrawType& draw, uint16_t type, uint32_t e, const Frame& f, float drawn_share) const;
    /// True when `type`'s impostor level is drawn (an atlas was set).
    [[nodiscard]] bool has_impostor(uint16_t type) const { return type < impostors_.size() && impostors_[type].atlas >= 0; }
    struct Impostor {
        int64_t atlas = -1;    ///< renderer id, -1 = none
        float cycle_s = 1.0f;  ///< walk cycle (clip seconds)
        float scale = 1.0f;    ///< the atlas's pictures drawn this many times as large
    };

    std::vector<std::pair<uint32_t, uint32_t>> topologies_;  ///< SurfaceView::topology_key -> renderer id
    std::vector<std::vector<uint32_t>> materials_;           ///< per type: renderer ids of its materials
    std::vector<glm::vec3> muscle_scratch_;                  ///< one character's muscle surface (overlays)
    std::vector<std::string> pass_names_;                    ///< per geometric level: its GPU pass label
    std::vector<Impostor> impostors_;                        ///< per type: its impostor atlas
    std::vector<ProxyInstance> fading_proxies_;              ///< this frame's dithered proxy boxes (appended last)
    std::vector<ProxyFade> fading_runs_;                     ///< their runs, relative to fading_proxies_
};

/// The colour a character is drawn in: the debug palette of `mode`, else white over a textured type's
/// materials, else the shaded proxy or skin tone.
glm::vec4 character_colour(DebugColour mode, const LodState& state, const AnimLod& anim, bool proxy, bool textured = false);

}  // namespace aloha
