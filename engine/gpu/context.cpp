#include "engine/gpu/context.hpp"

#include "engine/gpu/cpu_heap.hpp"
#include "engine/gpu/device_choice.hpp"
#include "engine/gpu/vk_error.hpp"

#include <cstdlib>
#include <cstring>

namespace aloha::gpu {
namespace {

constexpr const char* kValidationLayer = "VK_LAYER_KHRONOS_validation";
constexpr size_t kMaxKeptMessages = 256;

VKAPI_ATTR VkBool32 VKAPI_CALL debug_callback(VkDebugUtilsMessageSeverityFlagBitsEXT severity,
                                              VkDebugUtilsMessageTypeFlagsEXT /*types*/,
                                              const VkDebugUtilsMessengerCallbackDataEXT* data, void* user) {
    auto* log = static_cast<ValidationLog*>(user);
    const char* level = (severity & VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT) ? "error" : "warning";
    std::lock_guard<std::mutex> lock(log->mutex);
    ++log->count;
    if (log->messages.size() < kMaxKeptMessages)
        log->messages.push_back(std::string(level) + ": " + (data && data->pMessage ? data->pMessage : ""));
    return VK_FALSE;
}

VkDebugUtilsMessengerCreateInfoEXT messenger_info(ValidationLog* log) {
    VkDebugUtilsMessengerCreateInfoEXT info{};
    info.sType = VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT;
    info.messageSeverity =
        VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT;
    info.messageType = VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT |
                       VK_DEBUG_UTILS_MESSAGE_TYPE_PERFORMANCE_BIT_EXT;
    info.pfnUserCallback = debug_callback;
    info.pUserData = log;
    return info;
}

bool layer_present(const char* name) {
    uint32_t n = 0;
    if (vkEnumerateInstanceLayerProperties(&n, nullptr) != VK_SUCCESS) return false;
    std::vector<VkLayerProperties> layers(n);
    if (vkEnumerateInstanceLayerProperties(&n, layers.data()) != VK_SUCCESS) return false;
    for (const auto& l : layers)
        if (std::strcmp(l.layerName, name) == 0) return true;
    return false;
}

}  // namespace

Result<std::unique_ptr<Context>> Context::create(const ContextOptions& options) {
    std::unique_ptr<Context> ctx(new Context());
    Status s = ctx->init(options);
    if (!s) return s.error();
    return ctx;
}

Status Context::init(const ContextOptions& options) {
    if (options.log) log_ = options.log;
    // Device choice is parsed first so a bad ALOHA_DEVICE fails before any Vulkan work.
    std::string choice_text = options.device;
    std::string source = "ContextOptions::device";
    if (choice_text.empty()) {
        const char* env = std::getenv("ALOHA_DEVICE");
        if (env != nullptr) {
            choice_text = env;
            source = "ALOHA_DEVICE";
        }
    }
    Result<DeviceChoice> choice = parse_device_choice(choice_text, source);
    if (!choice) return choice.error();

    // Instance.
    std::vector<const char*> extensions;
    for (const std::string& e : options.instance_extensions) extensions.push_back(e.c_str());
    std::vector<const char*> layers;
    if (options.validation) {
        if (!layer_present(kValidationLayer))
            return gpu_error(std::string(kValidationLayer) +
                             " was requested but is not installed (Debian: vulkan-validationlayers)");
        layers.push_back(kValidationLayer);
        extensions.push_back(VK_EXT_DEBUG_UTILS_EXTENSION_NAME);
    }
    VkApplicationInfo app{};
    app.sType = VK_STRUCTURE_TYPE_APPLICATION_INFO;
    app.pApplicationName = options.app_name.c_str();
    app.pEngineName = "aloha";
    app.apiVersion = VK_API_VERSION_1_2;

    VkDebugUtilsMessengerCreateInfoEXT dbg = messenger_info(log_.get());
    const VkValidationFeatureEnableEXT enables[] = {VK_VALIDATION_FEATURE_ENABLE_SYNCHRONIZATION_VALIDATION_EXT};
    VkValidationFeaturesEXT features{};
    features.sType = VK_STRUCTURE_TYPE_VALIDATION_FEATURES_EXT;
    features.enabledValidationFeatureCount = 1;
    features.pEnabledValidationFeatures = enables;
    features.pNext = &dbg;  // the messenger also sees instance creation and destruction

    VkInstanceCreateInfo ici{};
    ici.sType = VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO;
    ici.pApplicationInfo = &app;
    ici.enabledLayerCount = static_cast<uint32_t>(layers.size());
    ici.ppEnabledLayerNames = layers.data();
    ici.enabledExtensionCount = static_cast<uint32_t>(extensions.size());
    ici.ppEnabledExtensionNames = extensions.data();
    if (options.validation) ici.pNext = &features;
    ALOHA_VK_RETURN(vkCreateInstance(&ici, nullptr, &instance_));

    if (options.validation) {
        auto create_messenger = reinterpret_cast<PFN_vkCreateDebugUtilsMessengerEXT>(
            vkGetInstanceProcAddr(instance_, "vkCreateDebugUtilsMessengerEXT"));
        if (create_messenger == nullptr) return gpu_error("vkCreateDebugUtilsMessengerEXT is not available");
        ALOHA_VK_RETURN(create_messenger(instance_, &dbg, nullptr, &messenger_));
    }

    // Physical device.
    uint32_t count = 0;
    ALOHA_VK_RETURN(vkEnumeratePhysicalDevices(instance_, &count, nullptr));
    std::vector<VkPhysicalDevice> physicals(count);
    ALOHA_VK_RETURN(vkEnumeratePhysicalDevices(instance_, &count, physicals.data()));
    std::vector<DeviceSummary> summaries(count);
    for (uint32_t i = 0; i < count; ++i) {
        VkPhysicalDeviceProperties p{};
        vkGetPhysicalDeviceProperties(physicals[i], &p);
        summaries[i].name = p.deviceName;
        summaries[i].type = static_cast<int>(p.deviceType);
        summaries[i].api_version = p.apiVersion;
        uint32_t nf = 0;
        vkGetPhysicalDeviceQueueFamilyProperties(physicals[i], &nf, nullptr);
        std::vector<VkQueueFamilyProperties> fams(nf);
        vkGetPhysicalDeviceQueueFamilyProperties(physicals[i], &nf, fams.data());
        for (const auto& f : fams)
            if (f.queueFlags & VK_QUEUE_GRAPHICS_BIT) summaries[i].has_graphics_queue = true;
    }
    Result<uint32_t> picked = pick_device(summaries, choice.value());
    if (!picked) return picked.error();
    physical_ = physicals[picked.value()];
    vkGetPhysicalDeviceProperties(physical_, &props_);
    vkGetPhysicalDeviceMemoryProperties(physical_, &mem_props_);
    if (options.keep_freed_heap && is_cpu_device()) (void)keep_freed_heap();

    uint32_t nf = 0;
    vkGetPhysicalDeviceQueueFamilyProperties(physical_, &nf, nullptr);
    std::vector<VkQueueFamilyProperties> fams(nf);
    vkGetPhysicalDeviceQueueFamilyProperties(physical_, &nf, fams.data());
    for (uint32_t i = 0; i < nf; ++i) {
        if (fams[i].queueFlags & VK_QUEUE_GRAPHICS_BIT) {
            queue_family_ = i;
            timestamp_valid_bits_ = fams[i].timestampValidBits;
            break;
        }
    }

    // Device extensions must all be supported.
    std::vector<const char*> dev_ext;
    if (!options.device_extensions.empty()) {
        uint32_t ne = 0;
        ALOHA_VK_RETURN(vkEnumerateDeviceExtensionProperties(physical_, nullptr, &ne, nullptr));
        std::vector<VkExtensionProperties> have(ne);
        ALOHA_VK_RETURN(vkEnumerateDeviceExtensionProperties(physical_, nullptr, &ne, have.data()));
        for (const std::string& want : options.device_extensions) {
            bool found = false;
            for (const auto& h : have) found = found || want == h.extensionName;
            if (!found)
                return gpu_error("device '" + std::string(props_.deviceName) + "' lacks extension " + want,
                                 VK_ERROR_EXTENSION_NOT_PRESENT);
            dev_ext.push_back(want.c_str());
        }
    }

    const float priority = 1.0f;
    VkDeviceQueueCreateInfo qci{};
    qci.sType = VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO;
    qci.queueFamilyIndex = queue_family_;
    qci.queueCount = 1;
    qci.pQueuePriorities = &priority;
    VkDeviceCreateInfo dci{};
    dci.sType = VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO;
    dci.queueCreateInfoCount = 1;
    dci.pQueueCreateInfos = &qci;
    dci.enabledExtensionCount = static_cast<uint32_t>(dev_ext.size());
    dci.ppEnabledExtensionNames = dev_ext.data();
    ALOHA_VK_RETURN(vkCreateDevice(physical_, &dci, nullptr, &device_));
    vkGetDeviceQueue(device_, queue_family_, 0, &queue_);

    VkCommandPoolCreateInfo pci{};
    pci.sType = VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO;
    pci.flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;
    pci.queueFamilyIndex = queue_family_;
    ALOHA_VK_RETURN(vkCreateCommandPool(device_, &pci, nullptr, &pool_));
    return {};
}

Context::~Context() {
    if (device_ != VK_NULL_HANDLE) {
        vkDeviceWaitIdle(device_);
        if (pool_ != VK_NULL_HANDLE) vkDestroyCommandPool(device_, pool_, nullptr);
        vkDestroyDevice(device_, nullptr);
    }
    if (messenger_ != VK_NULL_HANDLE) {
        auto destroy = reinterpret_cast<PFN_vkDestroyDebugUtilsMessengerEXT>(
            vkGetInstanceProcAddr(instance_, "vkDestroyDebugUtilsMessengerEXT"));
        if (destroy != nullptr) destroy(instance_, messenger_, nullptr);
    }
    if (instance_ != VK_NULL_HANDLE) vkDestroyInstance(instance_, nullptr);
}

Result<uint32_t> Context::find_memory_type(uint32_t type_bits, VkMemoryPropertyFlags wanted) const {
    for (uint32_t i = 0; i < mem_props_.memoryTypeCount; ++i)
        if ((type_bits & (1u << i)) && (mem_props_.memoryTypes[i].propertyFlags & wanted) == wanted) return i;
    return gpu_error("no memory type with flags " + std::to_string(wanted) + " among allowed types " +
                     std::to_string(type_bits));
}

Status Context::submit_once(const std::function<void(VkCommandBuffer)>& record) const {
    VkCommandBufferAllocateInfo ai{};
    ai.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO;
    ai.commandPool = pool_;
    ai.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
    ai.commandBufferCount = 1;
    VkCommandBuffer cmd = VK_NULL_HANDLE;
    ALOHA_VK_RETURN(vkAllocateCommandBuffers(device_, &ai, &cmd));
    VkFence fence = VK_NULL_HANDLE;
    auto cleanup = [&] {
        if (fence != VK_NULL_HANDLE) vkDestroyFence(device_, fence, nullptr);
        vkFreeCommandBuffers(device_, pool_, 1, &cmd);
    };
    VkCommandBufferBeginInfo bi{};
    bi.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO;
    bi.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
    VkResult r = vkBeginCommandBuffer(cmd, &bi);
    if (r != VK_SUCCESS) {
        cleanup();
        return vk_error("vkBeginCommandBuffer", r);
    }
    record(cmd);
    r = vkEndCommandBuffer(cmd);
    if (r != VK_SUCCESS) {
        cleanup();
        return vk_error("vkEndCommandBuffer", r);
    }
    VkFenceCreateInfo fi{};
    fi.sType = VK_STRUCTURE_TYPE_FENCE_CREATE_INFO;
    r = vkCreateFence(device_, &fi, nullptr, &fence);
    if (r != VK_SUCCESS) {
        cleanup();
        return vk_error("vkCreateFence", r);
    }
    VkSubmitInfo si{};
    si.sType = VK_STRUCTURE_TYPE_SUBMIT_INFO;
    si.commandBufferCount = 1;
    si.pCommandBuffers = &cmd;
    r = vkQueueSubmit(queue_, 1, &si, fence);
    if (r == VK_SUCCESS) r = vkWaitForFences(device_, 1, &fence, VK_TRUE, UINT64_MAX);
    const char* call = r == VK_SUCCESS ? "" : "vkQueueSubmit/vkWaitForFences (one-shot)";
    cleanup();
    if (r != VK_SUCCESS) return vk_error(call, r);
    return {};
}

Status Context::wait_idle() const {
    ALOHA_VK_RETURN(vkDeviceWaitIdle(device_));
    return {};
}

uint32_t Context::validation_message_count() const {
    std::lock_guard<std::mutex> lock(log_->mutex);
    return log_->count;
}

std::vector<std::string> Context::validation_messages() const {
    std::lock_guard<std::mutex> lock(log_->mutex);
    return log_->messages;
}

void Context::clear_validation_messages() {
    std::lock_guard<std::mutex> lock(log_->mutex);
    log_->count = 0;
    log_->messages.clear();
}

}  // namespace aloha::gpu
