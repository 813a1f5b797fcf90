#pragma once
// The headless Vulkan device gbufferlab renders with: no window, no surface, one queue that
// does graphics + compute + transfer. lavapipe (Mesa's CPU driver) is picked by default so
// results are reproducible everywhere; --device picks a real GPU.
#include <atomic>
#include <functional>
#include <mutex>
#include <string>
#include <vector>

#include <vulkan/vulkan.h>

#include "memory_recycler.h"
#include "shader_cache.h"

namespace gbl {

// Throws std::runtime_error naming the call and the VkResult: a failed Vulkan call on a working
// driver is our bug (or the driver's), not the user's.
#define VK_CHECK(call)                                                        \
    do {                                                                      \
        VkResult vkCheckResult_ = (call);                                     \
        if (vkCheckResult_ != VK_SUCCESS) ::gbl::vkFail(#call, vkCheckResult_, __FILE__, __LINE__); \
    } while (0)

[[noreturn]] void vkFail(const char* call, VkResult result, const char* file, int line);
const char* vkResultName(VkResult result);

struct DeviceOptions {
    // "" or "cpu": lavapipe (any CPU device); "gpu": the first discrete, then integrated GPU;
    // a number: the index printed by `gbufferlab devices`; otherwise a substring of the name.
    std::string device;
    // Validation layers: on when true, or when the environment has GBL_VALIDATION=1.
    bool validation = false;
};

struct PhysicalDeviceInfo {
    VkPhysicalDevice handle = VK_NULL_HANDLE;
    std::string name;
    std::string typeName;  // "cpu", "discrete-gpu", ...
    std::string driver;    // driver name + info
    VkPhysicalDeviceType type = VK_PHYSICAL_DEVICE_TYPE_OTHER;
};

class VulkanContext {
public:
    explicit VulkanContext(const DeviceOptions& options);
    ~VulkanContext();
    VulkanContext(const VulkanContext&) = delete;
    VulkanContext& operator=(const VulkanContext&) = delete;

    VkInstance instance = VK_NULL_HANDLE;
    VkPhysicalDevice physicalDevice = VK_NULL_HANDLE;
    VkDevice device = VK_NULL_HANDLE;
    VkQueue queue = VK_NULL_HANDLE;
    uint32_t queueFamily = 0;
    VkCommandPool commandPool = VK_NULL_HANDLE;
    VkPhysicalDeviceProperties properties{};
    VkPhysicalDeviceMemoryProperties memoryProperties{};
    PhysicalDeviceInfo info;
    bool validationEnabled = false;
    // Optional features the visibility buffer needs, enabled where the device has them:
    // gl_PrimitiveID in a fragment shader (geometryShader) and per-pixel texture indices in its
    // resolve (Vulkan 1.2 shaderSampledImageArrayNonUniformIndexing).
    bool primitiveIdInFragment = false;
    bool nonUniformSampledImageIndexing = false;
    // 64-bit float shader arithmetic is on (enabled whenever the device has it; the GPU evaluation's
    // sums need it).
    bool shaderFloat64 = false;

    // The persistent pipeline cache (shader_cache.h): loaded from disk when the device is made,
    // written back when the context is destroyed.
    VkPipelineCache pipelineCache() const { return pipelineCache_.handle(); }
    const std::string& pipelineCacheNote() const { return pipelineCache_.note(); }

    // Freed device memory kept for reuse on a GPU (memory_recycler.h; off on a CPU device).
    mutable MemoryRecycler recycler;

    // Records `record` into a one-time command buffer, submits it and waits. Thread-safe (the
    // command pool and queue are used under a lock, released while waiting): compare's image
    // writer downloads a run's HDR image while the next run renders. `record` may itself call
    // submitAndWait (GBL_EVAL_PROFILE submits each dispatch from inside a recording).
    void submitAndWait(const std::function<void(VkCommandBuffer)>& record) const;

    // Validation messages of severity error seen so far (tests assert this stays 0).
    int validationErrorCount() const { return validationErrors_.load(); }
    std::string firstValidationError() const;
    void noteValidationError(const char* message);

    uint32_t findMemoryType(uint32_t typeBits, VkMemoryPropertyFlags required, VkMemoryPropertyFlags preferred) const;
    bool isFormatSupported(VkFormat format, VkFormatFeatureFlags features) const;

private:
    void release() noexcept;
    VkDebugUtilsMessengerEXT messenger_ = VK_NULL_HANDLE;
    PersistentPipelineCache pipelineCache_;
    std::atomic<int> validationErrors_{0};
    mutable std::mutex messageMutex_;
    mutable std::recursive_mutex submitMutex_;
    std::string firstValidationError_;
};

// Enumerates devices without creating one (for `gbufferlab devices`). Throws UserError when no
// driver is installed.
std::vector<PhysicalDeviceInfo> listPhysicalDevices();

// Creates an instance or explains, in one line, why none can be created.
VkInstance createInstanceOrExplain(bool validation, bool* validationEnabled);

}  // namespace gbl
