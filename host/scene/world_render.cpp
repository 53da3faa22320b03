// The World's renderer hook-up (draw lists: systems/frame/draw_lists.hpp).
#include "host/scene/character_runtime.hpp"
#include "host/scene/world.hpp"

namespace aloha {

Status World::attach_renderer(CrowdRenderer* renderer, gpu::OffscreenTarget* target) {
    if (Status s = finish_rendering(); !s.ok()) return s;  // nothing of ours left in flight on the old one
    renderer_ = renderer;
    target_ = target;
    draws_.clear_impostors();
    impostor_reports_.clear();
    impostor_built_.clear();
    return prepare_drawing();
}

Status World::prepare_drawing() {
    if (Status s = reset_draws(); !s.ok()) return s;
    if (Status s = build_impostors(); !s.ok()) return s;
    return renderer_ ? renderer_->warm_up() : Status{};  // shader variants compiled now, not at a level's first draw
}

Status World::finish_rendering() {
    if (!renderer_) return {};
    Status s = renderer_->finish();
    if (s.ok()) last_gpu_ms_ = renderer_->last_gpu_ms();
    return s;
}

Status World::reset_draws() {
    draws_.reset();
    std::vector<std::string> pass_names;  // each level's name labels its GPU pass
    for (const auto& level : rules_.table().geom_levels) pass_names.push_back(level.name);
    draws_.set_pass_names(std::move(pass_names));
    if (!renderer_) return {};
    // Every type's materials and mesh levels registered now, not in the frame where a level first appears.
    refresh_type_views();
    return draws_.prepare(*renderer_, draw_types_);
}

void World::frame_settings(FrameInput& frame) const {
    frame.camera = render_camera();
    set_character_lighting(frame);
    frame.materials = options_.colour == DebugColour::Shaded;
}

}  // namespace aloha
