#include "host/tool/viewer_overlay.hpp"

#include "host/tool/viewer_pick.hpp"
#include "host/tool/viewer_rules.hpp"

#include <imgui.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <cstdio>
#include <string>

namespace aloha::tool {

namespace {

constexpr size_t kPlotFrames = 240;

// One histogram row: label, count and a bar of count / total.
void histogram_row(const char* label, uint32_t count, uint32_t total) {
    ImGui::TableNextRow();
    ImGui::TableSetColumnIndex(0);
    ImGui::TextUnformatted(label);
    ImGui::TableSetColumnIndex(1);
    ImGui::Text("%u", count);
    ImGui::TableSetColumnIndex(2);
    const float f = total ? static_cast<float>(count) / static_cast<float>(total) : 0.0f;
    char pct[32];
    std::snprintf(pct, sizeof pct, "%.1f%%", 100.0f * f);
    ImGui::ProgressBar(f, ImVec2(-1.0f, 0.0f), pct);
}

bool begin_histogram(const char* id) {
    if (!ImGui::BeginTable(id, 3, ImGuiTableFlags_RowBg | ImGuiTableFlags_SizingStretchProp)) return false;
    ImGui::TableSetupColumn("level / method", ImGuiTableColumnFlags_WidthStretch, 2.0f);
    ImGui::TableSetupColumn("count", ImGuiTableColumnFlags_WidthStretch, 1.0f);
    ImGui::TableSetupColumn("share", ImGuiTableColumnFlags_WidthStretch, 2.0f);
    ImGui::TableHeadersRow();
    return true;
}

void draw_playback(World& world, ViewerState& state) {
    ImGui::Text("%s: frame %llu, t = %.2f s, %zu characters", world.scene().name.c_str(),
                static_cast<unsigned long long>(world.frame()), static_cast<double>(world.time()),
                world.character_count());
    ImGui::Text("%.1f fps (window), GPU %.2f ms, %u draw calls", static_cast<double>(ImGui::GetIO().Framerate),
                state.gpu_ms, state.draw_calls);
    ImGui::Checkbox("paused (Space)", &state.paused);
    ImGui::SameLine();
    if (ImGui::Button("step")) state.step_once = true;
}

void draw_camera(ViewerCamera& camera, const World& world, const CameraKey& scene_key) {
    if (!ImGui::CollapsingHeader("Camera")) return;
    int mode = static_cast<int>(camera.mode);
    const char* names[kCameraModeCount] = {camera_mode_name(CameraMode::ScenePath), camera_mode_name(CameraMode::Orbit),
                                           camera_mode_name(CameraMode::Fly)};
    if (ImGui::Combo("mode (C)", &mode, names, kCameraModeCount)) camera.mode = static_cast<CameraMode>(mode);
    ImGui::SliderFloat("fov (deg)", &camera.fov_y_deg, 10.0f, 120.0f);
    ImGui::SliderFloat("fly speed (m/s)", &camera.fly.speed, 0.5f, 100.0f, "%.1f", ImGuiSliderFlags_Logarithmic);
    if (ImGui::Button("put free cameras at the scene camera")) camera.reset_from(world.scene().camera, scene_key);
    ImGui::TextDisabled("orbit: drag turns, right-drag pans, wheel zooms");
    ImGui::TextDisabled("fly: WASD move, Q/E down/up, Shift faster, drag looks");
    ImGui::TextDisabled("LOD follows the camera shown");
}

void draw_timings(World& world, const ViewerState& state) {
    if (!ImGui::CollapsingHeader("System timings", ImGuiTreeNodeFlags_DefaultOpen)) return;
    const Scheduler& sched = world.scheduler();
    const TimingRing& frame = sched.frame_timings();
    const double last = frame.size() ? static_cast<double>(frame.latest()) * 1e-6 : 0.0;
    ImGui::Text("CPU frame: %.3f ms (mean %.3f ms over %zu)", last, frame.mean_ns() * 1e-6, frame.size());
    if (!state.frame_ms.empty())
        ImGui::PlotLines("##frame_ms", state.frame_ms.data(), static_cast<int>(state.frame_ms.size()), 0,
                         "CPU frame ms", 0.0f, FLT_MAX, ImVec2(ImGui::GetContentRegionAvail().x, 50.0f));
    if (!ImGui::BeginTable("timings", 3, ImGuiTableFlags_RowBg | ImGuiTableFlags_SizingStretchProp)) return;
    ImGui::TableSetupColumn("system", ImGuiTableColumnFlags_WidthStretch, 2.0f);
    ImGui::TableSetupColumn("last ms", ImGuiTableColumnFlags_WidthStretch, 1.0f);
    ImGui::TableSetupColumn("mean ms", ImGuiTableColumnFlags_WidthStretch, 1.0f);
    ImGui::TableHeadersRow();
    for (uint32_t i = 0; i < sched.system_count(); ++i) {
        const TimingRing& t = sched.timings(i);
        ImGui::TableNextRow();
        ImGui::TableSetColumnIndex(0);
        ImGui::TextUnformatted(sched.names()[i].c_str());
        ImGui::TableSetColumnIndex(1);
        ImGui::Text("%.3f", t.size() ? static_cast<double>(t.latest()) * 1e-6 : 0.0);
        ImGui::TableSetColumnIndex(2);
        ImGui::Text("%.3f", t.mean_ns() * 1e-6);
    }
    ImGui::EndTable();
}

void draw_lod(World& world) {
    if (!ImGui::CollapsingHeader("Level of detail", ImGuiTreeNodeFlags_DefaultOpen)) return;
    const LodStats& s = world.lod_stats();
    const RuleTable& table = world.rules().table();
    ImGui::Text("visible %u, budget-demoted %u, geomorphing %u, cross-fading %u", s.visible, s.demoted, s.in_geomorph,
                s.in_crossfade);
    const uint32_t n = s.characters;
    if (ImGui::TreeNodeEx("geometric levels", ImGuiTreeNodeFlags_DefaultOpen)) {
        if (begin_histogram("geom")) {
            for (size_t l = 0; l < s.per_geom_level.size(); ++l)
                histogram_row(l < table.geom_levels.size() ? table.geom_levels[l].name.c_str() : "?",
                              s.per_geom_level[l], n);
            ImGui::EndTable();
        }
        ImGui::TreePop();
    }
    if (ImGui::TreeNodeEx("animation levels", ImGuiTreeNodeFlags_DefaultOpen)) {
        if (begin_histogram("anim")) {
            for (size_t l = 0; l < s.per_anim_level.size(); ++l)
                histogram_row(l < table.anim_levels.size() ? table.anim_levels[l].name.c_str() : "?",
                              s.per_anim_level[l], n);
            ImGui::EndTable();
        }
        ImGui::TreePop();
    }
    if (ImGui::TreeNodeEx("walk methods", ImGuiTreeNodeFlags_DefaultOpen)) {
        if (begin_histogram("walk")) {
            for (size_t m = 0; m < s.per_walk_method.size(); ++m)
                histogram_row(std::string(to_string(static_cast<WalkMethod>(m))).c_str(), s.per_walk_method[m], n);
            ImGui::EndTable();
        }
        ImGui::TreePop();
    }
    if (ImGui::TreeNode("geometric methods")) {
        if (begin_histogram("gmethod")) {
            for (size_t m = 0; m < s.per_geom_method.size(); ++m)
                histogram_row(std::string(to_string(static_cast<GeomMethod>(m))).c_str(), s.per_geom_method[m], n);
            ImGui::EndTable();
        }
        ImGui::TreePop();
    }
    if (ImGui::TreeNode("rules fired")) {
        if (begin_histogram("rule")) {
            for (size_t r = 0; r < s.per_rule.size(); ++r)
                histogram_row(r < table.rules.size() ? table.rules[r].name.c_str() : "?", s.per_rule[r], n);
            ImGui::EndTable();
        }
        ImGui::TreePop();
    }
}

void draw_colouring(World& world, ViewerState& state) {
    const char* names[] = {"shaded", "level", "rule", "method"};
    if (ImGui::Combo("colouring", &state.colour, names, 4)) world.set_colour(static_cast<DebugColour>(state.colour));
}

void draw_picker(World& world, ViewerState& state) {
    if (!ImGui::CollapsingHeader("Character (click one to pick)")) return;
    const int count = static_cast<int>(world.character_count());
    if (count == 0) {
        ImGui::TextUnformatted("no characters");
        return;
    }
    auto refs = character_group(world.registry()).span<CharacterRef>();
    if (state.has_pick) {
        const int found = find_character(refs, state.picked_ref);  // follow it across regrouping
        if (found >= 0) state.picked = found;
    }
    const int before = state.picked;
    ImGui::InputInt("index", &state.picked);
    ImGui::SameLine();
    ImGui::TextDisabled("of %d", count);
    state.picked = std::clamp(state.picked, 0, std::min(count, static_cast<int>(refs.size())) - 1);
    if (!state.has_pick || state.picked != before) {
        state.picked_ref = refs[static_cast<size_t>(state.picked)];
        state.has_pick = true;
    }
    const std::string text = world.explain(static_cast<uint32_t>(state.picked)).dump(2);
    ImGui::BeginChild("explain", ImVec2(0.0f, 260.0f), true, ImGuiWindowFlags_HorizontalScrollbar);
    ImGui::TextUnformatted(text.c_str());
    ImGui::EndChild();
}

// Edits of one rule; returns true when something changed.
bool edit_rule(RuleTable& t, uint32_t r, const std::vector<RuleThreshold>& thresholds) {
    bool changed = false;
    int g = t.rules[r].geom_level, a = t.rules[r].anim_level;
    auto geom_name = [](void* data, int i, const char** out) {
        *out = static_cast<RuleTable*>(data)->geom_levels[static_cast<size_t>(i)].name.c_str();
        return true;
    };
    auto anim_name = [](void* data, int i, const char** out) {
        *out = static_cast<RuleTable*>(data)->anim_levels[static_cast<size_t>(i)].name.c_str();
        return true;
    };
    bool levels = ImGui::Combo("geometry", &g, geom_name, &t, static_cast<int>(t.geom_levels.size()));
    levels |= ImGui::Combo("animation", &a, anim_name, &t, static_cast<int>(t.anim_levels.size()));
    if (levels) {
        set_rule_levels(t, r, static_cast<uint8_t>(g), static_cast<uint8_t>(a));
        changed = true;
    }
    const CompiledRule& c = t.compiled[r];
    int shown = 0;
    for (size_t i = 0; i < thresholds.size(); ++i) {
        const RuleThreshold& th = thresholds[i];
        if (th.rule != r) continue;
        ++shown;
        float v = threshold_value(t, th);
        std::string label = std::string(attribute_name(th.attribute)) + (th.upper ? " <=" : " >=");
        if (c.box_count > 1) label += " (case " + std::to_string(th.box - c.first_box + 1) + ")";
        ImGui::PushID(static_cast<int>(i));
        const float speed = std::max(0.001f, 0.005f * std::fabs(v));
        if (ImGui::DragFloat(label.c_str(), &v, speed, 0.0f, 0.0f, "%.4g")) {
            set_threshold(t, th, v);
            changed = true;
        }
        ImGui::PopID();
    }
    if (shown == 0) ImGui::TextDisabled(t.rules[r].unconditional ? "unconditional (fallback)" : "no numeric thresholds");
    return changed;
}

void draw_rules(World& world, ViewerState& state) {
    if (!ImGui::CollapsingHeader("Rules (live)")) return;
    RuleSet& rules = world.rules();
    if (state.edit_generation != rules.generation()) {
        state.edit = rules.table();
        state.edit_generation = rules.generation();
    }
    RuleTable& t = state.edit;
    ImGui::TextWrapped("%s (generation %u)", rules.path().c_str(), rules.generation());
    if (ImGui::Button("reload from file")) {
        auto group = character_group(world.registry());
        Status s = reload_rules_keep_state(rules, group.span<LodState>());
        state.rule_error = !s.ok();
        state.rule_message = s.ok() ? "reloaded " + rules.path() : s.error().to_string();
        for (const Error& e : rules.last_errors()) state.rule_message += "\n" + e.to_string();
    }
    bool changed = false;
    float band = t.hysteresis.band;
    float min_seconds = t.hysteresis.min_seconds;
    bool hyst = ImGui::SliderFloat("hysteresis band", &band, 0.0f, 1.0f, "%.3f");
    hyst |= ImGui::InputFloat("min seconds", &min_seconds, 0.05f, 0.5f, "%.3f");
    if (hyst) {
        set_hysteresis(t, band, min_seconds);
        changed = true;
    }
    const std::vector<RuleThreshold> thresholds = editable_thresholds(t);
    for (uint32_t r = 0; r < t.rules.size(); ++r) {
        ImGui::PushID(static_cast<int>(r));
        if (ImGui::TreeNode(t.rules[r].name.c_str())) {
            changed |= edit_rule(t, r, thresholds);
            ImGui::TreePop();
        }
        ImGui::PopID();
    }
    if (changed) {
        Status s = apply_edited_table(rules, t);
        state.rule_error = !s.ok();
        state.rule_message = s.ok() ? "applied (generation " + std::to_string(rules.generation()) + ")"
                                    : s.error().to_string();
        if (s.ok()) state.edit_generation = rules.generation();  // our copy is the table in use
    }
    if (!state.rule_message.empty()) {
        const ImVec4 colour = state.rule_error ? ImVec4(1.0f, 0.45f, 0.4f, 1.0f) : ImVec4(0.6f, 0.9f, 0.6f, 1.0f);
        ImGui::PushStyleColor(ImGuiCol_Text, colour);
        ImGui::TextWrapped("%s", state.rule_message.c_str());
        ImGui::PopStyleColor();
    }
}

}  // namespace

void pick_at(World& world, ViewerState& state, const RenderCamera& camera, glm::vec2 viewport, glm::vec2 mouse_px) {
    auto group = character_group(world.registry());
    const int i = pick_character(group.span<Transform>(), group.span<Bounds>(), camera, viewport, mouse_px, 40.0f);
    if (i < 0) return;
    state.picked = i;
    state.picked_ref = group.span<CharacterRef>()[static_cast<size_t>(i)];
    state.has_pick = true;
}

void append_pick_marker(World& world, const ViewerState& state, std::vector<LineSegment>& lines) {
    if (!state.show_overlay || !state.has_pick) return;
    auto group = character_group(world.registry());
    const int i = find_character(group.span<CharacterRef>(), state.picked_ref);
    if (i < 0) return;
    const auto k = static_cast<size_t>(i);
    marker_lines(group.span<Transform>()[k], group.span<Bounds>()[k], glm::vec4(1.0f, 0.85f, 0.1f, 1.0f), lines);
}

void record_frame_time(ViewerState& state, const World& world) {
    const TimingRing& frame = world.scheduler().frame_timings();
    if (frame.size() == 0) return;
    if (state.frame_ms.size() >= kPlotFrames) state.frame_ms.erase(state.frame_ms.begin());
    state.frame_ms.push_back(static_cast<float>(static_cast<double>(frame.latest()) * 1e-6));
}

void draw_overlay(World& world, ViewerState& state, ViewerCamera& camera, const CameraKey& scene_key) {
    if (!state.show_overlay) return;
    const ImGuiIO& io = ImGui::GetIO();
    ImGui::SetNextWindowPos(ImVec2(10.0f, 10.0f), ImGuiCond_FirstUseEver);
    ImGui::SetNextWindowSize(ImVec2(440.0f, std::max(200.0f, io.DisplaySize.y - 20.0f)), ImGuiCond_FirstUseEver);
    ImGui::SetNextWindowBgAlpha(0.85f);
    if (ImGui::Begin("ALOHA (H hides)")) {
        draw_playback(world, state);
        draw_colouring(world, state);
        draw_camera(camera, world, scene_key);
        draw_picker(world, state);
        draw_rules(world, state);
        draw_timings(world, state);
        draw_lod(world);
    }
    ImGui::End();
}

}  // namespace aloha::tool
