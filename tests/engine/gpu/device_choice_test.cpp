// Device choice: parsing of ALOHA_DEVICE / ContextOptions::device and the selection policy, plus the
// end-to-end check that a bad ALOHA_DEVICE makes Context::create fail with an error naming it.
#include "engine/gpu/context.hpp"
#include "engine/gpu/device_choice.hpp"

#include <gtest/gtest.h>
#include <vulkan/vulkan.h>

#include <cstdlib>

namespace aloha::gpu {
namespace {

TEST(DeviceChoice, ParsesNamesAndIndices) {
    using K = DeviceChoice::Kind;
    EXPECT_EQ(parse_device_choice("", "x").value().kind, K::Auto);
    EXPECT_EQ(parse_device_choice("auto", "x").value().kind, K::Auto);
    EXPECT_EQ(parse_device_choice("lavapipe", "x").value().kind, K::Cpu);
    EXPECT_EQ(parse_device_choice("CPU", "x").value().kind, K::Cpu);
    EXPECT_EQ(parse_device_choice("gpu", "x").value().kind, K::Gpu);
    Result<DeviceChoice> idx = parse_device_choice("2", "x");
    ASSERT_TRUE(idx.ok());
    EXPECT_EQ(idx.value().kind, K::Index);
    EXPECT_EQ(idx.value().index, 2u);
}

TEST(DeviceChoice, RejectsUnknownTextNamingTheSource) {
    Result<DeviceChoice> bad = parse_device_choice("radeon9000", "ALOHA_DEVICE");
    ASSERT_FALSE(bad.ok());
    EXPECT_NE(bad.error().message.find("ALOHA_DEVICE='radeon9000'"), std::string::npos) << bad.error().message;
    EXPECT_FALSE(parse_device_choice("-1", "x").ok());
    EXPECT_FALSE(parse_device_choice("1.5", "x").ok());
}

std::vector<DeviceSummary> fake_devices() {
    const uint32_t v13 = VK_API_VERSION_1_3;
    return {{"llvmpipe", VK_PHYSICAL_DEVICE_TYPE_CPU, v13, true},
            {"old gpu", VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU, VK_API_VERSION_1_1, true},
            {"igpu", VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU, v13, true},
            {"dgpu", VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU, v13, true}};
}

TEST(DeviceChoice, AutoPrefersDiscreteThenIntegratedThenCpu) {
    std::vector<DeviceSummary> d = fake_devices();
    EXPECT_EQ(pick_device(d, {}).value(), 3u);  // dgpu; "old gpu" is below Vulkan 1.2
    d.pop_back();
    EXPECT_EQ(pick_device(d, {}).value(), 2u);
    d.pop_back();
    EXPECT_EQ(pick_device(d, {}).value(), 0u);
    EXPECT_FALSE(pick_device(std::span<const DeviceSummary>{}, {}).ok());
}

TEST(DeviceChoice, ExplicitChoices) {
    const std::vector<DeviceSummary> d = fake_devices();
    EXPECT_EQ(pick_device(d, {DeviceChoice::Kind::Cpu, 0}).value(), 0u);
    EXPECT_EQ(pick_device(d, {DeviceChoice::Kind::Gpu, 0}).value(), 3u);
    EXPECT_EQ(pick_device(d, {DeviceChoice::Kind::Index, 2}).value(), 2u);
    EXPECT_FALSE(pick_device(d, {DeviceChoice::Kind::Index, 1}).ok());  // unusable (Vulkan 1.1)
    EXPECT_FALSE(pick_device(d, {DeviceChoice::Kind::Index, 9}).ok());
    const std::vector<DeviceSummary> cpu_only = {d[0]};
    Result<uint32_t> none = pick_device(cpu_only, {DeviceChoice::Kind::Gpu, 0});
    ASSERT_FALSE(none.ok());
    EXPECT_NE(none.error().message.find("llvmpipe"), std::string::npos) << "error lists the devices seen";
}

TEST(Context, BadAlohaDeviceEnvironmentIsAnError) {
    const char* old = std::getenv("ALOHA_DEVICE");
    const std::string saved = old ? old : "";
    ::setenv("ALOHA_DEVICE", "not-a-device", 1);
    Result<std::unique_ptr<Context>> ctx = Context::create({});
    if (old) ::setenv("ALOHA_DEVICE", saved.c_str(), 1); else ::unsetenv("ALOHA_DEVICE");
    ASSERT_FALSE(ctx.ok());
    EXPECT_EQ(ctx.error().path, "ALOHA_DEVICE");
    EXPECT_NE(ctx.error().message.find("not-a-device"), std::string::npos) << ctx.error().message;
}

TEST(Context, OutOfRangeIndexIsAnError) {
    ContextOptions o;
    o.device = "99";
    Result<std::unique_ptr<Context>> ctx = Context::create(o);
    ASSERT_FALSE(ctx.ok());
    EXPECT_NE(ctx.error().message.find("99"), std::string::npos) << ctx.error().message;
}

TEST(Context, LavapipeWithValidationStartsAndStopsCleanly) {
    auto log = std::make_shared<ValidationLog>();
    {
        ContextOptions o;
        o.validation = true;
        o.device = "lavapipe";
        o.log = log;
        Result<std::unique_ptr<Context>> ctx = Context::create(o);
        ASSERT_TRUE(ctx.ok()) << ctx.error().to_string();
        EXPECT_TRUE(ctx.value()->is_cpu_device());
        EXPECT_TRUE(ctx.value()->validation_enabled());
        EXPECT_TRUE(ctx.value()->submit_once([](VkCommandBuffer) {}).ok());
    }
    // The log outlives the context, so messages from vkDestroyDevice/vkDestroyInstance would show here.
    std::lock_guard<std::mutex> lock(log->mutex);
    EXPECT_EQ(log->count, 0u) << (log->messages.empty() ? "" : log->messages.front());
}

}  // namespace
}  // namespace aloha::gpu
