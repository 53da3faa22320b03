#include "host/tool/session.hpp"

#include "engine/gpu/png.hpp"
#include "host/scene/scene_loader.hpp"
#include "systems/lod/rule_table.hpp"

#include <algorithm>
#include <cstdlib>
#include <thread>
#include <utility>

namespace aloha::tool {

Session::~Session() {
    if (world) (void)world->attach_renderer(nullptr, nullptr);
    renderer.reset();
    target = gpu::OffscreenTarget();
    context.reset();
}

DebugColour colour_from_option(const std::string& name) {
    if (name == "level") return DebugColour::ByLodLevel;
    if (name == "rule") return DebugColour::ByRule;
    if (name == "method") return DebugColour::ByMotionMethod;
    return DebugColour::Shaded;
}

HardwareInfo hardware_info(const gpu::Context* context, unsigned threads) {
    HardwareInfo hw;
    hw.cores = threads ? threads : std::max(1u, std::thread::hardware_concurrency());
    if (!context) return hw;
    hw.gpu_name = context->device_name();
    hw.software_rasterizer = context->is_cpu_device();
    VkPhysicalDeviceMemoryProperties memory{};
    vkGetPhysicalDeviceMemoryProperties(context->physical_device(), &memory);
    uint64_t bytes = 0;
    for (uint32_t h = 0; h < memory.memoryHeapCount; ++h)
        if (memory.memoryHeaps[h].flags & VK_MEMORY_HEAP_DEVICE_LOCAL_BIT) bytes += memory.memoryHeaps[h].size;
    hw.gpu_memory_mb = bytes >> 20;
    return hw;
}

namespace {

// The World names an option it cannot honour by its field (ErrorKind::Option, path "characters");
// the tool says which flag set it, and what to do.
Error name_flag(Error e) {
    if (e.kind != ErrorKind::Option) return e;
    if (e.path == "lod") e.message += "; use --characters to profile fewer";
    e.path = e.path == "lod" ? "--lod off" : "--" + e.path;
    if (e.file.empty()) std::swap(e.file, e.path);
    return e;
}

}  // namespace

Result<std::unique_ptr<Session>> open_session(const CliOptions& options, bool render) {
    auto session = std::make_unique<Session>();
    auto scene = load_scene(options.scene);
    if (!scene.ok()) return scene.error();
    session->scene = std::move(scene.value());
    if (options.width) session->scene.width = *options.width;
    if (options.height) session->scene.height = *options.height;
    if (options.frames) session->scene.frames = *options.frames;
    WorldOptions wo;
    wo.threads = options.threads;
    wo.lod = options.lod;
    wo.bake_cache = options.cache;
    if (!options.cache_dir.empty()) wo.bake_cache_dir = options.cache_dir;
    wo.bake_cache_max_bytes = options.cache_max_bytes;
    wo.budget_ms = options.budget_ms;
    wo.seed_override = options.seed.value_or(0);
    wo.characters = options.characters;
    wo.colour = colour_from_option(options.colour);
    if (options.overlay.find("bones") != std::string::npos) wo.overlay |= kOverlayBones;
    if (options.overlay.find("muscles") != std::string::npos) wo.overlay |= kOverlayMuscles;
    if (options.overlay.find("springs") != std::string::npos) wo.overlay |= kOverlaySprings;
    // Nothing displays refined skins without a renderer, but export --out writes one.
    wo.keep_refined_surfaces = render || (options.command == "export" && !options.out.empty());
    wo.budget = options.budget;
    wo.budget_animation_ms = options.budget_animation_ms;
    wo.budget_geometry_ms = options.budget_geometry_ms;
    wo.budget_single_ms = options.budget_single_ms;
    wo.occlusion = options.occlusion;
    if (options.impostor_elevations) wo.impostor_elevations = *options.impostor_elevations;
    if (options.impostor_share_px) wo.impostor_share_px = *options.impostor_share_px;
    // Tools that read every character's pose every frame (metrics, export, the fidelity reference) need
    // poses no stage of the frame reads.
    wo.pose_every_character = options.motion_metrics || options.fidelity || options.command == "export";
    if (!options.tier.empty()) wo.tier = options.tier;
    // The fidelity probe reads each frame back and renders its reference with the same renderer before the
    // next step: no frame is left in flight (the overlap policy would otherwise read the probe's GPU time).
    wo.overlap_gpu = render && options.command == "profile" && !options.fidelity ? options.gpu_overlap : GpuOverlap::Off;
    gpu::ContextOptions co;
    const char* env = std::getenv("ALOHA_VALIDATION");
    co.validation = options.validation || (env && std::string(env) == "1");
    co.device = options.device;
    if (render) {
        auto ctx = gpu::Context::create(co);
        if (!ctx.ok()) return ctx.error();
        session->context = std::move(ctx.value());
        wo.hardware = hardware_info(session->context.get(), options.threads);
    } else if (!wo.tier) {
        // No renderer, but rules with "default_tier": "auto" still need the GPU's facts: look once.
        auto rules = load_rules(session->scene.rules);
        if (rules.ok() && rules.value().tier_auto) {
            gpu::ContextOptions probe;
            probe.device = options.device;
            auto ctx = gpu::Context::create(probe);
            wo.hardware = hardware_info(ctx.ok() ? ctx.value().get() : nullptr, options.threads);
        }
    }
    auto world = World::create(session->scene, wo);
    if (!world.ok()) return name_flag(world.error());
    session->world = std::move(world.value());
    if (!render) return session;
    RendererOptions ro;
    ro.far_layer_below_px = options.far_layer_px;
    ro.far_layer_meshes_below_px = options.far_layer_meshes_px;
    ro.distant_layer_below_px = options.distant_layer_px.value_or(0.0f);
    ro.blend_texture_mips = options.blend_texture_mips;
    ro.impostor_views = options.impostor_views;
    if (options.far_layer_alpha_test) ro.far_layer_alpha_test = *options.far_layer_alpha_test;
    if (options.max_texture_side) ro.max_texture_side = *options.max_texture_side;
    ro.pass_timestamps = options.gpu_passes;
    ro.constant_fragments = options.constant_fragments;
    auto renderer = CrowdRenderer::create(*session->context, ro);
    if (!renderer.ok()) return renderer.error();
    session->renderer = std::move(renderer.value());
    auto target = gpu::OffscreenTarget::create(*session->context, session->scene.width, session->scene.height);
    if (!target.ok()) return target.error();
    session->target = std::move(target.value());
    if (Status s = session->world->attach_renderer(session->renderer.get(), &session->target); !s.ok()) return s.error();
    return session;
}

Status check_validation(const Session& session) {
    if (!session.context || session.context->validation_message_count() == 0) return {};
    std::string text = std::to_string(session.context->validation_message_count()) + " Vulkan validation message(s):";
    for (const auto& m : session.context->validation_messages()) text += "\n  " + m;
    return make_error("", text);
}

Status save_frame(Session& session, const std::string& path) {
    auto image = session.target.read_back(*session.context);
    if (!image.ok()) return image.error();
    return gpu::write_png(path, image.value().width, image.value().height, image.value().pixels);
}

}  // namespace aloha::tool
