// targets/vulkan/vulkan_context.hpp — a headless Vulkan 1.3 device under the Khronos validation
// layer, for running emitted programs (lavapipe on machines without a GPU).
//
// Every message the validation layer (or the loader) reports at warning or error severity is
// counted and printed through a debug-utils messenger: a run is clean only when the count is 0.
// Entry points come from volk (Debian's libvulkan-volk-dev), so nothing links libvulkan directly.
#pragma once

#include <volk.h>

#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace penumbra::vulkan {

class Context {
public:
    enum class Failure { none, no_device, error };

    // Instance with VK_LAYER_KHRONOS_validation and VK_EXT_debug_utils (both required: a run that
    // cannot be validated is refused), the first physical device with a graphics queue, and a
    // device with Vulkan 1.3's dynamic rendering. On failure returns nullopt and sets *failure
    // (no_device: no Vulkan driver or no device, a reason to skip; error: anything else) and *error.
    static std::optional<Context> create(Failure* failure, std::string* error);

    ~Context();
    Context(Context&& other) noexcept;
    Context& operator=(Context&& other) = delete;
    Context(const Context&) = delete;
    Context& operator=(const Context&) = delete;

    VkDevice device() const { return device_; }
    VkPhysicalDevice physical_device() const { return physical_; }
    const VkPhysicalDeviceProperties& properties() const { return properties_; }
    // True when the device has (and the context enabled) the logicOp feature: logic_op OR passes.
    bool logic_op() const { return logic_op_; }
    // Warning and error messages reported so far (validation layer, loader, driver).
    int messages() const { return *messages_; }
    // The same count, readable after the context is destroyed: destroying the device reports
    // every object left alive.
    std::shared_ptr<const int> message_counter() const { return messages_; }

    // A memory type with `required` properties among `type_bits`, or -1.
    int memory_type(std::uint32_t type_bits, VkMemoryPropertyFlags required) const;

    // Records commands with `record` into a fresh primary command buffer, submits it and waits.
    // Returns an empty string or what failed.
    std::string submit(const std::function<void(VkCommandBuffer)>& record) const;

private:
    Context() = default;
    void release() noexcept;

    VkInstance instance_ = VK_NULL_HANDLE;
    VkDebugUtilsMessengerEXT messenger_ = VK_NULL_HANDLE;
    VkPhysicalDevice physical_ = VK_NULL_HANDLE;
    VkPhysicalDeviceProperties properties_{};
    VkDevice device_ = VK_NULL_HANDLE;
    VkQueue queue_ = VK_NULL_HANDLE;
    std::uint32_t queue_family_ = 0;
    bool logic_op_ = false;
    VkCommandPool pool_ = VK_NULL_HANDLE;
    // Heap-allocated so that the messenger's user pointer survives a move of the Context.
    std::shared_ptr<int> messages_ = std::make_shared<int>(0);
};

// "VK_ERROR_OUT_OF_DEVICE_MEMORY" for the common results, else the number.
std::string result_name(VkResult result);

} // namespace penumbra::vulkan
