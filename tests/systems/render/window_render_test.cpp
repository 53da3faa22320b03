// CrowdRenderer into a GLFW window (X11, e.g. Xvfb): 10 frames presented through the swapchain, the last
// one read back before presenting and checked for the proxy box's palette colour, a resize that recreates
// the swapchain, and validation reporting nothing. Skipped when DISPLAY is unset.
#include "engine/gpu/window_target.hpp"
#include "systems/render/crowd_renderer.hpp"
#include "systems/render/debug_colours.hpp"

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include <cstdlib>

namespace aloha {
namespace {

struct GlfwSession {
    bool ok = false;
    GlfwSession() { ok = glfwInit() == GLFW_TRUE; }
    ~GlfwSession() {
        if (ok) glfwTerminate();
    }
};

TEST(WindowTarget, PresentsTenFramesAndReadsBackTheLast) {
    const char* display = std::getenv("DISPLAY");
    if (display == nullptr || *display == '\0') GTEST_SKIP() << "DISPLAY is unset (run under Xvfb)";
    GlfwSession glfw;
    if (!glfw.ok) GTEST_SKIP() << "glfwInit failed on DISPLAY=" << display;
    glfwWindowHint(GLFW_CLIENT_API, GLFW_NO_API);
    GLFWwindow* window = glfwCreateWindow(160, 120, "aloha window test", nullptr, nullptr);
    ASSERT_NE(window, nullptr);

    Result<gpu::ContextOptions> opt = gpu::window_context_options(/*validation=*/true);
    ASSERT_TRUE(opt.ok()) << opt.error().to_string();
    opt.value().device = "lavapipe";
    Result<std::unique_ptr<gpu::Context>> ctx = gpu::Context::create(opt.value());
    ASSERT_TRUE(ctx.ok()) << ctx.error().to_string();
    {
        Result<std::unique_ptr<gpu::WindowTarget>> target = gpu::WindowTarget::create(*ctx.value(), window, false);
        ASSERT_TRUE(target.ok()) << target.error().to_string();
        gpu::WindowTarget& wt = *target.value();
        RendererOptions ro;
        ro.colour_format = wt.colour_format();
        Result<std::unique_ptr<CrowdRenderer>> renderer = CrowdRenderer::create(*ctx.value(), ro);
        ASSERT_TRUE(renderer.ok()) << renderer.error().to_string();

        // One unit box filling the middle of an orthographic view [-2, 2] x [-1.5, 1.5]: 40 px per unit.
        const std::vector<ProxyInstance> proxies = {{glm::mat4(1.0f), colour_for_level(3)}};
        FrameInput frame;
        frame.camera.view = glm::lookAt(glm::vec3(0, 0, 5), glm::vec3(0), glm::vec3(0, 1, 0));
        frame.camera.proj = glm::ortho(-2.0f, 2.0f, -1.5f, 1.5f, 0.1f, 20.0f);
        frame.proxies = proxies;
        frame.ambient = 1.0f;  // unlit: the palette colour exactly
        frame.clear_colour = {0.0f, 0.0f, 0.0f, 1.0f};

        gpu::Rgba8Image last;
        for (int i = 0; i < 10; ++i) {
            glfwPollEvents();
            Result<gpu::AcquiredImage> img = wt.acquire();
            ASSERT_TRUE(img.ok()) << img.error().to_string();
            ASSERT_NE(img.value().view.framebuffer, VK_NULL_HANDLE);
            Status s = renderer.value()->render(frame, img.value().view,
                                                FrameSync{img.value().acquired, img.value().render_done});
            ASSERT_TRUE(s.ok()) << s.error().to_string();
            if (i == 9) {
                Result<gpu::Rgba8Image> rb = wt.read_back(img.value());
                ASSERT_TRUE(rb.ok()) << rb.error().to_string();
                last = std::move(rb).value();
            }
            ASSERT_TRUE(wt.present(img.value()).ok());
        }
        ASSERT_EQ(last.width, 160u);
        ASSERT_EQ(last.height, 120u);
        // Box: 40 x 40 px centred, exact palette colour (ambient 1, colour multiple of 1/255); edges at
        // pixel boundaries (40 px per unit, box edges at +-0.5 -> columns 60..99, rows 40..79).
        const glm::u8vec4 want = to_rgba8(colour_for_level(3));
        int inside = 0, clear = 0;
        for (uint32_t y = 0; y < last.height; ++y)
            for (uint32_t x = 0; x < last.width; ++x) {
                const uint8_t* p = &last.pixels[(y * last.width + x) * 4];
                if (p[0] == want.r && p[1] == want.g && p[2] == want.b) ++inside;
                else if (p[0] == 0 && p[1] == 0 && p[2] == 0) ++clear;
            }
        EXPECT_NEAR(inside, 1600, 81) << "40 x 40 +- (40 + 40 + 1)";
        EXPECT_EQ(inside + clear, 160 * 120);

        // Resize: the next acquire rebuilds the swapchain at the new size.
        const uint32_t gen = wt.swapchain_generation();
        glfwSetWindowSize(window, 200, 100);
        for (int i = 0; i < 20 && wt.extent().width != 200; ++i) {
            glfwPollEvents();
            Result<gpu::AcquiredImage> img = wt.acquire();
            ASSERT_TRUE(img.ok()) << img.error().to_string();
            if (img.value().view.framebuffer == VK_NULL_HANDLE) continue;
            ASSERT_TRUE(renderer.value()
                            ->render(frame, img.value().view, FrameSync{img.value().acquired, img.value().render_done})
                            .ok());
            ASSERT_TRUE(wt.present(img.value()).ok());
        }
        EXPECT_EQ(wt.extent().width, 200u);
        EXPECT_EQ(wt.extent().height, 100u);
        EXPECT_GT(wt.swapchain_generation(), gen);
        ASSERT_TRUE(renderer.value()->finish().ok());
    }
    EXPECT_EQ(ctx.value()->validation_message_count(), 0u)
        << (ctx.value()->validation_messages().empty() ? "" : ctx.value()->validation_messages().front());
    ctx.value().reset();
    glfwDestroyWindow(window);
}

}  // namespace
}  // namespace aloha
