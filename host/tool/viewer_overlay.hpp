// The viewer's Dear ImGui overlay: playback and camera controls, per-system timings, the LOD
// histograms, a character picker showing World::explain, the debug colouring selector and the live
// rule editor (thresholds, target levels, hysteresis; applied with RuleSet::set_table, plus a reload
// from file; neither resets character state). Call between ImGui::NewFrame and ImGui::Render.
#pragma once

#include "host/scene/world.hpp"
#include "host/tool/viewer_camera.hpp"

#include <cstdint>
#include <string>
#include <vector>

namespace aloha::tool {

/// What the overlay edits between frames (owned by the viewer loop).
struct ViewerState {
    bool show_overlay = true;        ///< H toggles
    bool paused = false;             ///< Space toggles: the World is not stepped
    bool step_once = false;          ///< set by the "step" button; the loop clears it after stepping
    int picked = 0;                  ///< character index (group order) shown in the picker
    bool has_pick = false;           ///< picked_ref names a character (followed across regrouping)
    CharacterRef picked_ref;         ///< the picked character (type, id)
    int colour = 0;                  ///< DebugColour as int (Shaded, ByLodLevel, ByRule, ByMotionMethod)
    std::string rule_message;        ///< outcome of the last rule apply/reload, shown in the editor
    bool rule_error = false;         ///< rule_message is an error
    RuleTable edit;                  ///< working copy of the rule table being edited
    uint32_t edit_generation = ~0u;  ///< RuleSet generation `edit` was copied from (~0 = none yet)
    double gpu_ms = -1.0;            ///< the window renderer's last GPU frame time (-1: unknown)
    uint32_t draw_calls = 0;         ///< the window renderer's draw calls last frame
    std::vector<float> frame_ms;     ///< recent CPU frame times for the plot (ring, newest last)
};

/// Draws the overlay for `world` and applies what the user changed: colouring (World::set_colour),
/// rule edits (RuleSet::set_table) and reloads (reload_rules_keep_state), camera mode and lens.
/// `scene_key` is the scene camera's placement this frame (for "reset free cameras here").
void draw_overlay(World& world, ViewerState& state, ViewerCamera& camera, const CameraKey& scene_key);

/// Picks the character under `mouse_px` (a click in the view), if any within 40 px.
void pick_at(World& world, ViewerState& state, const RenderCamera& camera, glm::vec2 viewport, glm::vec2 mouse_px);

/// Appends the picked character's marker box to `lines` (nothing when none is picked or the overlay is off).
void append_pick_marker(World& world, const ViewerState& state, std::vector<LineSegment>& lines);

/// Records the latest CPU frame time into state.frame_ms (keeps the last 240).
void record_frame_time(ViewerState& state, const World& world);

}  // namespace aloha::tool
