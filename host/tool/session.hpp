// What every aloha subcommand sets up: the scene (with command-line overrides), the World, and for
// rendering commands a Vulkan context, a crowd renderer and an offscreen target.
#pragma once

#include "engine/gpu/context.hpp"
#include "engine/gpu/offscreen_target.hpp"
#include "host/scene/world.hpp"
#include "host/tool/cli_args.hpp"

#include <memory>

namespace aloha::tool {

/// A loaded scene, its World and (optionally) a headless renderer.
struct Session {
    SceneDesc scene;
    std::unique_ptr<World> world;
    std::unique_ptr<gpu::Context> context;
    std::unique_ptr<CrowdRenderer> renderer;
    gpu::OffscreenTarget target;

    /// Tears the renderer down before the context.
    ~Session();
};

/// Loads the scene named in `options`, applies overrides (--width/--height/--seed/--characters/--lod/
/// --budget*/--tier/--occlusion/--threads) and builds the World with the hardware facts for an "auto"
/// tier; with `render` also the GPU side.
Result<std::unique_ptr<Session>> open_session(const CliOptions& options, bool render);

/// The hardware facts tier selection uses: cores (`threads`, or every core when 0) and, with a
/// context, its device's name, whether it rasterises in software, and its device-local memory.
HardwareInfo hardware_info(const gpu::Context* context, unsigned threads);

/// The DebugColour named by --colour.
DebugColour colour_from_option(const std::string& name);

/// Fails, listing them, when Vulkan validation reported any message during the session.
Status check_validation(const Session& session);

/// Writes the target's current image to `path` as PNG.
Status save_frame(Session& session, const std::string& path);

}  // namespace aloha::tool
