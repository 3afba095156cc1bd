#include "vulkan_context.hpp"

#include <cstdio>
#include <cstring>
#include <utility>

namespace penumbra::vulkan {
namespace {

constexpr const char* validation_layer = "VK_LAYER_KHRONOS_validation";

VKAPI_ATTR VkBool32 VKAPI_CALL on_message(VkDebugUtilsMessageSeverityFlagBitsEXT severity,
                                          VkDebugUtilsMessageTypeFlagsEXT, const VkDebugUtilsMessengerCallbackDataEXT* data,
                                          void* user) {
    if (severity < VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT) return VK_FALSE;
    ++*static_cast<int*>(user);
    std::fprintf(stderr, "vulkan %s: %s\n", severity >= VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT ? "error" : "warning",
                 data && data->pMessage ? data->pMessage : "(no text)");
    return VK_FALSE; // never abort the call that caused it
}

bool has_layer(const char* name) {
    std::uint32_t count = 0;
    vkEnumerateInstanceLayerProperties(&count, nullptr);
    std::vector<VkLayerProperties> layers(count);
    vkEnumerateInstanceLayerProperties(&count, layers.data());
    for (const VkLayerProperties& l : layers)
        if (std::strcmp(l.layerName, name) == 0) return true;
    return false;
}

} // namespace

std::string result_name(VkResult result) {
    switch (result) {
    case VK_SUCCESS: return "VK_SUCCESS";
    case VK_ERROR_OUT_OF_HOST_MEMORY: return "VK_ERROR_OUT_OF_HOST_MEMORY";
    case VK_ERROR_OUT_OF_DEVICE_MEMORY: return "VK_ERROR_OUT_OF_DEVICE_MEMORY";
    case VK_ERROR_INITIALIZATION_FAILED: return "VK_ERROR_INITIALIZATION_FAILED";
    case VK_ERROR_DEVICE_LOST: return "VK_ERROR_DEVICE_LOST";
    case VK_ERROR_LAYER_NOT_PRESENT: return "VK_ERROR_LAYER_NOT_PRESENT";
    case VK_ERROR_EXTENSION_NOT_PRESENT: return "VK_ERROR_EXTENSION_NOT_PRESENT";
    case VK_ERROR_FEATURE_NOT_PRESENT: return "VK_ERROR_FEATURE_NOT_PRESENT";
    case VK_ERROR_INCOMPATIBLE_DRIVER: return "VK_ERROR_INCOMPATIBLE_DRIVER";
    case VK_ERROR_FORMAT_NOT_SUPPORTED: return "VK_ERROR_FORMAT_NOT_SUPPORTED";
    default: return "VkResult " + std::to_string(static_cast<int>(result));
    }
}

std::optional<Context> Context::create(Failure* failure, std::string* error) {
    auto fail = [&](Failure kind, std::string message) -> std::optional<Context> {
        *failure = kind;
        *error = std::move(message);
        return std::nullopt;
    };
    if (volkInitialize() != VK_SUCCESS) return fail(Failure::no_device, "no Vulkan loader (libvulkan.so.1)");
    if (volkGetInstanceVersion() < VK_API_VERSION_1_3)
        return fail(Failure::no_device, "the Vulkan loader is older than 1.3");
    if (!has_layer(validation_layer))
        return fail(Failure::error, std::string(validation_layer) + " is not installed (Debian: vulkan-validationlayers)");

    Context c;
    VkDebugUtilsMessengerCreateInfoEXT messenger{VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT};
    messenger.messageSeverity = VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT;
    messenger.messageType = VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT |
                            VK_DEBUG_UTILS_MESSAGE_TYPE_PERFORMANCE_BIT_EXT;
    messenger.pfnUserCallback = on_message;
    messenger.pUserData = c.messages_.get();

    VkApplicationInfo app{VK_STRUCTURE_TYPE_APPLICATION_INFO};
    app.pApplicationName = "penumbra-vulkan-run";
    app.apiVersion = VK_API_VERSION_1_3;
    const char* extensions[] = {VK_EXT_DEBUG_UTILS_EXTENSION_NAME, VK_EXT_VALIDATION_FEATURES_EXTENSION_NAME};
    // Beyond the default checks: synchronization validation (hazards between passes).
    const VkValidationFeatureEnableEXT enables[] = {VK_VALIDATION_FEATURE_ENABLE_SYNCHRONIZATION_VALIDATION_EXT};
    VkValidationFeaturesEXT features{VK_STRUCTURE_TYPE_VALIDATION_FEATURES_EXT};
    features.pNext = &messenger; // also reports what happens while the instance is created
    features.enabledValidationFeatureCount = 1;
    features.pEnabledValidationFeatures = enables;
    VkInstanceCreateInfo instance_info{VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO};
    instance_info.pNext = &features;
    instance_info.pApplicationInfo = &app;
    instance_info.enabledLayerCount = 1;
    instance_info.ppEnabledLayerNames = &validation_layer;
    instance_info.enabledExtensionCount = 2;
    instance_info.ppEnabledExtensionNames = extensions;
    if (VkResult r = vkCreateInstance(&instance_info, nullptr, &c.instance_); r != VK_SUCCESS)
        return fail(r == VK_ERROR_INCOMPATIBLE_DRIVER ? Failure::no_device : Failure::error,
                    r == VK_ERROR_INCOMPATIBLE_DRIVER ? "no Vulkan driver (Debian: mesa-vulkan-drivers provides lavapipe)"
                                                      : "vkCreateInstance: " + result_name(r));
    volkLoadInstanceOnly(c.instance_);
    if (VkResult r = vkCreateDebugUtilsMessengerEXT(c.instance_, &messenger, nullptr, &c.messenger_); r != VK_SUCCESS)
        return fail(Failure::error, "vkCreateDebugUtilsMessengerEXT: " + result_name(r));

    std::uint32_t count = 0;
    vkEnumeratePhysicalDevices(c.instance_, &count, nullptr);
    std::vector<VkPhysicalDevice> devices(count);
    vkEnumeratePhysicalDevices(c.instance_, &count, devices.data());
    for (VkPhysicalDevice d : devices) {
        VkPhysicalDeviceProperties p;
        vkGetPhysicalDeviceProperties(d, &p);
        if (p.apiVersion < VK_API_VERSION_1_3) continue;
        std::uint32_t families = 0;
        vkGetPhysicalDeviceQueueFamilyProperties(d, &families, nullptr);
        std::vector<VkQueueFamilyProperties> props(families);
        vkGetPhysicalDeviceQueueFamilyProperties(d, &families, props.data());
        for (std::uint32_t f = 0; f < families && !c.physical_; ++f)
            if (props[f].queueFlags & VK_QUEUE_GRAPHICS_BIT) {
                c.physical_ = d;
                c.properties_ = p;
                c.queue_family_ = f;
            }
        if (c.physical_) break;
    }
    if (!c.physical_)
        return fail(Failure::no_device, "no Vulkan 1.3 device with a graphics queue (" + std::to_string(count) +
                                            " device(s); Debian: mesa-vulkan-drivers provides lavapipe)");

    const float priority = 1.0f;
    VkDeviceQueueCreateInfo queue{VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO};
    queue.queueFamilyIndex = c.queue_family_;
    queue.queueCount = 1;
    queue.pQueuePriorities = &priority;
    VkPhysicalDeviceVulkan13Features features13{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES};
    features13.dynamicRendering = VK_TRUE;
    VkPhysicalDeviceFeatures supported{}, enabled{};
    vkGetPhysicalDeviceFeatures(c.physical_, &supported);
    enabled.logicOp = supported.logicOp; // the slicing of 64 and 128 slices ORs bits into its target
    c.logic_op_ = supported.logicOp == VK_TRUE;
    VkDeviceCreateInfo device_info{VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO};
    device_info.pNext = &features13;
    device_info.pEnabledFeatures = &enabled;
    device_info.queueCreateInfoCount = 1;
    device_info.pQueueCreateInfos = &queue;
    if (VkResult r = vkCreateDevice(c.physical_, &device_info, nullptr, &c.device_); r != VK_SUCCESS)
        return fail(Failure::error, "vkCreateDevice: " + result_name(r));
    volkLoadDevice(c.device_);
    vkGetDeviceQueue(c.device_, c.queue_family_, 0, &c.queue_);
    VkCommandPoolCreateInfo pool{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
    pool.queueFamilyIndex = c.queue_family_;
    pool.flags = VK_COMMAND_POOL_CREATE_TRANSIENT_BIT;
    if (VkResult r = vkCreateCommandPool(c.device_, &pool, nullptr, &c.pool_); r != VK_SUCCESS)
        return fail(Failure::error, "vkCreateCommandPool: " + result_name(r));
    *failure = Failure::none;
    return c;
}

Context::Context(Context&& o) noexcept
    : instance_(std::exchange(o.instance_, VK_NULL_HANDLE)), messenger_(std::exchange(o.messenger_, VK_NULL_HANDLE)),
      physical_(o.physical_), properties_(o.properties_), device_(std::exchange(o.device_, VK_NULL_HANDLE)),
      queue_(o.queue_), queue_family_(o.queue_family_), logic_op_(o.logic_op_),
      pool_(std::exchange(o.pool_, VK_NULL_HANDLE)), messages_(std::move(o.messages_)) {}

Context::~Context() { release(); }

void Context::release() noexcept {
    if (device_) {
        vkDeviceWaitIdle(device_);
        if (pool_) vkDestroyCommandPool(device_, pool_, nullptr);
        vkDestroyDevice(device_, nullptr);
    }
    if (messenger_) vkDestroyDebugUtilsMessengerEXT(instance_, messenger_, nullptr);
    if (instance_) vkDestroyInstance(instance_, nullptr);
    device_ = VK_NULL_HANDLE;
    instance_ = VK_NULL_HANDLE;
}

int Context::memory_type(std::uint32_t type_bits, VkMemoryPropertyFlags required) const {
    VkPhysicalDeviceMemoryProperties memory;
    vkGetPhysicalDeviceMemoryProperties(physical_, &memory);
    for (std::uint32_t i = 0; i < memory.memoryTypeCount; ++i)
        if ((type_bits & (1u << i)) && (memory.memoryTypes[i].propertyFlags & required) == required)
            return static_cast<int>(i);
    return -1;
}

std::string Context::submit(const std::function<void(VkCommandBuffer)>& record) const {
    VkCommandBufferAllocateInfo allocate{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
    allocate.commandPool = pool_;
    allocate.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
    allocate.commandBufferCount = 1;
    VkCommandBuffer cmd = VK_NULL_HANDLE;
    if (VkResult r = vkAllocateCommandBuffers(device_, &allocate, &cmd); r != VK_SUCCESS)
        return "vkAllocateCommandBuffers: " + result_name(r);
    VkCommandBufferBeginInfo begin{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
    begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
    vkBeginCommandBuffer(cmd, &begin);
    record(cmd);
    std::string error;
    if (VkResult r = vkEndCommandBuffer(cmd); r != VK_SUCCESS) error = "vkEndCommandBuffer: " + result_name(r);
    if (error.empty()) {
        VkSubmitInfo submit{VK_STRUCTURE_TYPE_SUBMIT_INFO};
        submit.commandBufferCount = 1;
        submit.pCommandBuffers = &cmd;
        if (VkResult r = vkQueueSubmit(queue_, 1, &submit, VK_NULL_HANDLE); r != VK_SUCCESS)
            error = "vkQueueSubmit: " + result_name(r);
        else if (VkResult w = vkQueueWaitIdle(queue_); w != VK_SUCCESS)
            error = "vkQueueWaitIdle: " + result_name(w);
    }
    vkFreeCommandBuffers(device_, pool_, 1, &cmd);
    return error;
}

} // namespace penumbra::vulkan
