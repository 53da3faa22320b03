// The World's renderer hook-up (draw lists: systems/frame/draw_lists.hpp).
#include "engine/scene/character_runtime.hpp"
#include "engine/scene/world.hpp"

namespace aloha {

Status World::attach_renderer(CrowdRenderer* renderer, gpu::OffscreenTarget* target) {
    renderer_ = renderer;
    target_ = target;
    draws_.reset();
    return {};
}

void World::frame_settings(FrameInput& frame) const {
    frame.camera = render_camera();
    set_character_lighting(frame);
    frame.materials = options_.colour == DebugColour::Shaded;
}

}  // namespace aloha
