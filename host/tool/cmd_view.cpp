// `aloha view SCENE`: the World stepped every frame and drawn into a GLFW window by a CrowdRenderer,
// with the Dear ImGui overlay (viewer_overlay) on top. Closes on window close or after --frames N;
// --out FILE saves the last frame (read back from the swapchain) as PNG; --validation reports every
// Vulkan validation message (ImGui's backend included) and then fails.
#include "engine/gpu/png.hpp"
#include "engine/gpu/window_target.hpp"
#include "host/tool/commands.hpp"
#include "host/tool/session.hpp"
#include "host/tool/viewer_camera.hpp"
#include "host/tool/viewer_gui.hpp"
#include "host/tool/viewer_overlay.hpp"

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

namespace aloha::tool {

namespace {

std::string g_glfw_error;  // last GLFW error text (GLFW reports errors through a callback)

void glfw_error(int code, const char* text) { g_glfw_error = "GLFW error " + std::to_string(code) + ": " + text; }

// GLFW for the lifetime of the command.
struct GlfwScope {
    bool ok = false;
    GlfwScope() {
        glfwSetErrorCallback(glfw_error);
        ok = glfwInit() == GLFW_TRUE;
    }
    ~GlfwScope() {
        if (ok) glfwTerminate();
    }
};

// The window's GPU objects, destroyed in reverse order of creation (GUI, renderer, swapchain, context).
struct WindowGpu {
    std::shared_ptr<gpu::ValidationLog> log = std::make_shared<gpu::ValidationLog>();
    std::unique_ptr<gpu::Context> context;
    std::unique_ptr<gpu::WindowTarget> target;
    std::unique_ptr<CrowdRenderer> renderer;
    std::unique_ptr<GuiLayer> gui;
    ~WindowGpu() {
        gui.reset();
        if (renderer) (void)renderer->finish();
        renderer.reset();
        target.reset();
        context.reset();
    }
};

Status open_gpu(WindowGpu& g, GLFWwindow* window, const CliOptions& options) {
    Result<gpu::ContextOptions> co = gpu::window_context_options(options.validation);
    if (!co.ok()) return co.error();
    co.value().device = options.device;
    co.value().log = g.log;
    auto ctx = gpu::Context::create(co.value());
    if (!ctx.ok()) return ctx.error();
    g.context = std::move(ctx.value());
    // Scripted runs (--frames) need not wait for vertical blank.
    auto target = gpu::WindowTarget::create(*g.context, window, /*vsync=*/!options.frames.has_value());
    if (!target.ok()) return target.error();
    g.target = std::move(target.value());
    RendererOptions ro;
    ro.far_layer_below_px = options.far_layer_px;
    ro.far_layer_meshes_below_px = options.far_layer_meshes_px;
    ro.distant_layer_below_px = options.distant_layer_px.value_or(0.0f);
    ro.blend_texture_mips = options.blend_texture_mips;
    ro.impostor_views = options.impostor_views;
    if (options.far_layer_alpha_test) ro.far_layer_alpha_test = *options.far_layer_alpha_test;
    if (options.max_texture_side) ro.max_texture_side = *options.max_texture_side;
    ro.colour_format = g.target->colour_format();
    auto renderer = CrowdRenderer::create(*g.context, ro);
    if (!renderer.ok()) return renderer.error();
    g.renderer = std::move(renderer.value());
    auto gui = GuiLayer::create(*g.context, window, *g.target);
    if (!gui.ok()) return gui.error();
    g.gui = std::move(gui.value());
    return {};
}

// Keyboard and mouse: toggles, then the free cameras (only what ImGui does not claim).
void handle_input(GLFWwindow* window, ViewerCamera& camera, ViewerState& state, float dt) {
    const ImGuiIO& io = ImGui::GetIO();
    if (!io.WantCaptureKeyboard) {
        if (ImGui::IsKeyPressed(GLFW_KEY_H, false)) state.show_overlay = !state.show_overlay;
        if (ImGui::IsKeyPressed(GLFW_KEY_SPACE, false)) state.paused = !state.paused;
        if (ImGui::IsKeyPressed(GLFW_KEY_C, false))
            camera.mode = static_cast<CameraMode>((static_cast<int>(camera.mode) + 1) % kCameraModeCount);
        if (ImGui::IsKeyPressed(GLFW_KEY_ESCAPE, false)) glfwSetWindowShouldClose(window, GLFW_TRUE);
        if (camera.mode == CameraMode::Fly) {
            auto down = [&](int key) { return glfwGetKey(window, key) == GLFW_PRESS ? 1.0f : 0.0f; };
            const glm::vec3 move{down(GLFW_KEY_D) - down(GLFW_KEY_A), down(GLFW_KEY_E) - down(GLFW_KEY_Q),
                                 down(GLFW_KEY_W) - down(GLFW_KEY_S)};
            const float boost = down(GLFW_KEY_LEFT_SHIFT) > 0.0f ? 4.0f : 1.0f;
            camera.fly.move(move, dt, boost);
        }
    }
    if (io.WantCaptureMouse) return;
    const float dx = io.MouseDelta.x, dy = io.MouseDelta.y;
    const bool moved = std::isfinite(dx) && std::isfinite(dy) && (dx != 0.0f || dy != 0.0f);
    if (camera.mode == CameraMode::Orbit) {
        if (moved && io.MouseDown[0]) camera.orbit.rotate(dx, dy);
        if (moved && io.MouseDown[1]) camera.orbit.pan(dx, dy);
        if (io.MouseWheel != 0.0f) camera.orbit.zoom(io.MouseWheel);
    } else if (camera.mode == CameraMode::Fly) {
        if (moved && (io.MouseDown[0] || io.MouseDown[1])) camera.fly.look(dx, dy);
    }
}

// The scene camera's placement for the frame the World ran last.
CameraKey scene_key(const World& world) {
    const SceneDesc& scene = world.scene();
    if (scene.camera.keys.empty()) return CameraKey{};
    const float t = world.frame() > 0 ? std::max(0.0f, world.time() - scene.dt) : 0.0f;
    return sample_camera(scene.camera, t);
}

// What the last drawn image was seen with (for click picking).
struct Shown {
    RenderCamera camera;
    glm::vec2 viewport{0.0f};
};

// One window image: crowd frame (+ the picked character's marker), overlay, optional readback into
// *saved, present. The ImGui frame must have been started (it is rendered or discarded here).
Status draw_image(WindowGpu& g, World& world, const ViewerState& state, const ViewerCamera& camera, Shown* shown,
                  gpu::Rgba8Image* saved) {
    Result<gpu::AcquiredImage> acquired = g.target->acquire();
    if (!acquired.ok()) {
        g.gui->discard_frame();
        return acquired.error();
    }
    const gpu::AcquiredImage& img = acquired.value();
    if (img.view.framebuffer == VK_NULL_HANDLE) {  // minimised
        g.gui->discard_frame();
        return {};
    }
    const RenderLists& lists = world.render_lists();
    FrameInput input;
    world.frame_settings(input);
    const float aspect = static_cast<float>(img.view.extent.width) / static_cast<float>(img.view.extent.height);
    input.camera = camera.matrices(scene_key(world), aspect);
    shown->camera = input.camera;
    shown->viewport = {static_cast<float>(img.view.extent.width), static_cast<float>(img.view.extent.height)};
    std::vector<LineSegment> lines(lists.lines.begin(), lists.lines.end());
    append_pick_marker(world, state, lines);
    input.meshes = lists.meshes;
    input.proxies = lists.proxies;
    input.proxy_fades = lists.proxy_fades;
    input.impostors = lists.impostors;
    input.lines = lines;
    if (Status s = g.renderer->render(input, img.view, FrameSync{img.acquired, VK_NULL_HANDLE}); !s.ok()) {
        g.gui->discard_frame();
        return s;
    }
    if (Status s = g.gui->submit(img); !s.ok()) return s;
    if (saved != nullptr) {
        auto rb = g.target->read_back(img);
        if (!rb.ok()) return rb.error();
        *saved = std::move(rb.value());
    }
    return g.target->present(img);
}

// Prints every validation message the run produced; true when there were none.
bool report_validation(const gpu::ValidationLog& log) {
    std::lock_guard<std::mutex> lock(log.mutex);
    for (const std::string& m : log.messages) print_error("validation " + m);
    if (log.count > log.messages.size())
        print_error("validation: " + std::to_string(log.count - log.messages.size()) + " more message(s)");
    return log.count == 0;
}

}  // namespace

int run_view(const CliOptions& options) {
    if (!options.out.empty() && !check_can_write(options.out, options.force)) return 1;
    auto opened = open_session(options, /*render=*/false);
    if (!opened.ok()) {
        print_error(opened.error().to_string());
        return 1;
    }
    Session& session = *opened.value();
    World& world = *session.world;

    GlfwScope glfw;
    if (!glfw.ok) {
        print_error("cannot open a window (is DISPLAY set?): " + g_glfw_error);
        return 1;
    }
    glfwWindowHint(GLFW_CLIENT_API, GLFW_NO_API);
    const std::string title = "aloha view - " + world.scene().name;
    GLFWwindow* window = glfwCreateWindow(static_cast<int>(session.scene.width), static_cast<int>(session.scene.height),
                                          title.c_str(), nullptr, nullptr);
    if (window == nullptr) {
        print_error("cannot create a " + std::to_string(session.scene.width) + "x" +
                    std::to_string(session.scene.height) + " window: " + g_glfw_error);
        return 1;
    }

    int code = 0;
    uint64_t frames_shown = 0;
    gpu::Rgba8Image last;
    std::shared_ptr<gpu::ValidationLog> log;
    {
        WindowGpu g;
        log = g.log;
        if (Status s = open_gpu(g, window, options); !s.ok()) {
            print_error(s.error().to_string());
            code = 1;
        } else if (Status a = world.attach_renderer(g.renderer.get(), nullptr); !a.ok()) {
            // Registers the World's topologies with the window's renderer; with no offscreen target the
            // World's own Render system draws nothing, this loop draws instead.
            print_error(a.error().to_string());
            code = 1;
        }
        ViewerState state;
        state.colour = static_cast<int>(world.options().colour);
        ViewerCamera camera;
        camera.reset_from(world.scene().camera, scene_key(world));
        const bool scripted = options.frames.has_value();
        const uint64_t limit = options.frames.value_or(0);
        Shown shown;
        double previous = glfwGetTime();
        while (code == 0 && !glfwWindowShouldClose(window) && (!scripted || frames_shown < limit)) {
            glfwPollEvents();
            const double now = glfwGetTime();
            const float dt = static_cast<float>(std::min(now - previous, 0.1));
            previous = now;
            g.gui->new_frame();
            handle_input(window, camera, state, dt);
            const ImGuiIO& io = ImGui::GetIO();
            if (!io.WantCaptureMouse && io.MouseReleased[0] && io.MouseDragMaxDistanceSqr[0] < 16.0f &&
                shown.viewport.x > 0.0f)  // a click, not a drag
                pick_at(world, state, shown.camera, shown.viewport, {io.MousePos.x, io.MousePos.y});
            if (!state.paused || state.step_once) {
                // The LOD follows what the window shows: the free camera and the window's size.
                int fb_w = 0, fb_h = 0;
                glfwGetFramebufferSize(window, &fb_w, &fb_h);
                if (fb_w > 0 && fb_h > 0)
                    world.set_view_override(camera.mode == CameraMode::ScenePath ? std::nullopt
                                                                               : std::optional<CameraKey>(camera.placement(scene_key(world))),
                                            camera.fov_y_deg, glm::vec2(float(fb_w), float(fb_h)));
                world.step();
                record_frame_time(state, world);
                state.step_once = false;
            }
            draw_overlay(world, state, camera, scene_key(world));
            const bool save = !options.out.empty() && scripted && frames_shown + 1 == limit;
            if (Status s = draw_image(g, world, state, camera, &shown, save ? &last : nullptr); !s.ok()) {
                print_error(s.error().to_string());
                code = 1;
            }
            state.gpu_ms = g.renderer->last_gpu_ms();
            state.draw_calls = g.renderer->last_draw_count();
            ++frames_shown;
        }
        // Closed by the user: draw the final state once more to save it.
        if (code == 0 && !options.out.empty() && !scripted) {
            g.gui->new_frame();
            draw_overlay(world, state, camera, scene_key(world));
            if (Status s = draw_image(g, world, state, camera, &shown, &last); !s.ok()) {
                print_error(s.error().to_string());
                code = 1;
            }
        }
        (void)world.attach_renderer(nullptr, nullptr);
    }  // GPU objects gone: destruction-time validation messages are in the log too
    glfwDestroyWindow(window);

    if (code == 0 && !options.out.empty()) {
        if (last.pixels.empty()) {
            print_error(options.out + ": no frame was drawn (window minimised?), nothing written");
            code = 1;
        } else if (Status s = gpu::write_png(options.out, last.width, last.height, last.pixels); !s.ok()) {
            print_error(s.error().to_string());
            code = 1;
        }
    }
    if (options.validation && !report_validation(*log)) code = 1;
    if (code == 0 && !options.quiet) {
        std::cout << "viewed " << frames_shown << " frame(s) of " << options.scene << " ("
                  << world.character_count() << " characters)";
        if (!options.out.empty()) std::cout << "; last frame written to " << options.out;
        std::cout << "\n";
    }
    return code;
}

}  // namespace aloha::tool
