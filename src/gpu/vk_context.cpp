#include "vk_context.h"

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <stdexcept>

#include "env_flag.h"
#include "error.h"

namespace gbl {

const char* vkResultName(VkResult result) {
    switch (result) {
#define GBL_CASE(x) \
    case x:         \
        return #x;
        GBL_CASE(VK_SUCCESS)
        GBL_CASE(VK_NOT_READY)
        GBL_CASE(VK_TIMEOUT)
        GBL_CASE(VK_INCOMPLETE)
        GBL_CASE(VK_ERROR_OUT_OF_HOST_MEMORY)
        GBL_CASE(VK_ERROR_OUT_OF_DEVICE_MEMORY)
        GBL_CASE(VK_ERROR_INITIALIZATION_FAILED)
        GBL_CASE(VK_ERROR_DEVICE_LOST)
        GBL_CASE(VK_ERROR_MEMORY_MAP_FAILED)
        GBL_CASE(VK_ERROR_LAYER_NOT_PRESENT)
        GBL_CASE(VK_ERROR_EXTENSION_NOT_PRESENT)
        GBL_CASE(VK_ERROR_FEATURE_NOT_PRESENT)
        GBL_CASE(VK_ERROR_INCOMPATIBLE_DRIVER)
        GBL_CASE(VK_ERROR_TOO_MANY_OBJECTS)
        GBL_CASE(VK_ERROR_FORMAT_NOT_SUPPORTED)
        GBL_CASE(VK_ERROR_FRAGMENTED_POOL)
        GBL_CASE(VK_ERROR_OUT_OF_POOL_MEMORY)
#undef GBL_CASE
        default:
            return "VK_ERROR_(unknown)";
    }
}

void vkFail(const char* call, VkResult result, const char* file, int line) {
    if (result == VK_ERROR_OUT_OF_DEVICE_MEMORY || result == VK_ERROR_OUT_OF_HOST_MEMORY)
        throw UserError(std::string("out of memory in ") + call + " (" + vkResultName(result) +
                        "); try a smaller --size");
    throw std::runtime_error(std::string(file) + ":" + std::to_string(line) + ": " + call + " failed with " +
                             vkResultName(result));
}

namespace {

constexpr const char* kValidationLayer = "VK_LAYER_KHRONOS_validation";

VKAPI_ATTR VkBool32 VKAPI_CALL onDebugMessage(VkDebugUtilsMessageSeverityFlagBitsEXT severity,
                                              VkDebugUtilsMessageTypeFlagsEXT,
                                              const VkDebugUtilsMessengerCallbackDataEXT* data, void* user) {
    if (severity & VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT) {
        auto* ctx = static_cast<VulkanContext*>(user);
        if (ctx->validationErrorCount() < 5) std::fprintf(stderr, "vulkan validation error: %s\n", data->pMessage);
        ctx->noteValidationError(data->pMessage);
    }
    return VK_FALSE;
}

bool hasLayer(const char* name) {
    uint32_t count = 0;
    vkEnumerateInstanceLayerProperties(&count, nullptr);
    std::vector<VkLayerProperties> layers(count);
    vkEnumerateInstanceLayerProperties(&count, layers.data());
    for (const auto& l : layers)
        if (std::strcmp(l.layerName, name) == 0) return true;
    return false;
}

const char* deviceTypeName(VkPhysicalDeviceType type) {
    switch (type) {
        case VK_PHYSICAL_DEVICE_TYPE_CPU: return "cpu";
        case VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU: return "discrete-gpu";
        case VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU: return "integrated-gpu";
        case VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU: return "virtual-gpu";
        default: return "other";
    }
}

std::vector<PhysicalDeviceInfo> describeDevices(VkInstance instance) {
    uint32_t count = 0;
    VK_CHECK(vkEnumeratePhysicalDevices(instance, &count, nullptr));
    std::vector<VkPhysicalDevice> handles(count);
    VK_CHECK(vkEnumeratePhysicalDevices(instance, &count, handles.data()));
    std::vector<PhysicalDeviceInfo> infos;
    for (VkPhysicalDevice h : handles) {
        VkPhysicalDeviceDriverProperties driver{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_DRIVER_PROPERTIES};
        VkPhysicalDeviceProperties2 props{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2, &driver};
        vkGetPhysicalDeviceProperties2(h, &props);
        PhysicalDeviceInfo info;
        info.handle = h;
        info.name = props.properties.deviceName;
        info.type = props.properties.deviceType;
        info.typeName = deviceTypeName(info.type);
        info.driver = std::string(driver.driverName) + " " + driver.driverInfo;
        infos.push_back(info);
    }
    return infos;
}

size_t pickDevice(const std::vector<PhysicalDeviceInfo>& devices, const std::string& wanted) {
    auto findType = [&](VkPhysicalDeviceType t) -> int {
        for (size_t i = 0; i < devices.size(); ++i)
            if (devices[i].type == t) return int(i);
        return -1;
    };
    std::string known;
    for (size_t i = 0; i < devices.size(); ++i)
        known += (i ? ", " : "") + std::to_string(i) + ": " + devices[i].name + " (" + devices[i].typeName + ")";
    if (wanted.empty() || wanted == "cpu") {
        int i = findType(VK_PHYSICAL_DEVICE_TYPE_CPU);
        if (i >= 0) return size_t(i);
        if (wanted == "cpu")
            throwUserError("--device cpu: no CPU Vulkan device (lavapipe) found; install mesa-vulkan-drivers (devices: " +
                           known + ")");
        return 0;
    }
    if (wanted == "gpu") {
        int i = findType(VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU);
        if (i < 0) i = findType(VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU);
        if (i < 0) throwUserError("--device gpu: no GPU found (devices: " + known + ")");
        return size_t(i);
    }
    if (!wanted.empty() && wanted.find_first_not_of("0123456789") == std::string::npos) {
        size_t i = std::stoul(wanted);
        if (i >= devices.size()) throwUserError("--device " + wanted + ": no such device index (devices: " + known + ")");
        return i;
    }
    for (size_t i = 0; i < devices.size(); ++i)
        if (devices[i].name.find(wanted) != std::string::npos) return i;
    throwUserError("--device " + wanted + ": no device name contains '" + wanted + "' (devices: " + known + ")");
}

}  // namespace

VkInstance createInstanceOrExplain(bool validation, bool* validationEnabled) {
    VkApplicationInfo app{VK_STRUCTURE_TYPE_APPLICATION_INFO};
    app.pApplicationName = "gbufferlab";
    app.apiVersion = VK_API_VERSION_1_3;

    std::vector<const char*> layers, extensions;
    bool useValidation = validation && hasLayer(kValidationLayer);
    if (validation && !useValidation)
        std::fprintf(stderr, "gbufferlab: warning: validation requested but %s is not installed "
                             "(apt-get install vulkan-validationlayers)\n", kValidationLayer);
    if (useValidation) {
        layers.push_back(kValidationLayer);
        extensions.push_back(VK_EXT_DEBUG_UTILS_EXTENSION_NAME);
    }
    VkInstanceCreateInfo info{VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO};
    info.pApplicationInfo = &app;
    info.enabledLayerCount = uint32_t(layers.size());
    info.ppEnabledLayerNames = layers.data();
    info.enabledExtensionCount = uint32_t(extensions.size());
    info.ppEnabledExtensionNames = extensions.data();
    VkInstance instance = VK_NULL_HANDLE;
    VkResult r = vkCreateInstance(&info, nullptr, &instance);
    if (r == VK_ERROR_INCOMPATIBLE_DRIVER || r == VK_ERROR_INITIALIZATION_FAILED)
        throwUserError("no Vulkan driver found; install one: apt-get install mesa-vulkan-drivers "
                       "(lavapipe, the CPU driver) or your GPU vendor's driver");
    if (r == VK_ERROR_LAYER_NOT_PRESENT)
        throwUserError("Vulkan validation layer missing; apt-get install vulkan-validationlayers, or unset GBL_VALIDATION");
    VK_CHECK(r);
    if (validationEnabled) *validationEnabled = useValidation;
    return instance;
}

std::vector<PhysicalDeviceInfo> listPhysicalDevices() {
    VkInstance instance = createInstanceOrExplain(false, nullptr);
    auto devices = describeDevices(instance);
    vkDestroyInstance(instance, nullptr);
    return devices;
}

VulkanContext::VulkanContext(const DeviceOptions& options) {
    const bool wantValidation = options.validation || envFlag("GBL_VALIDATION");
    instance = createInstanceOrExplain(wantValidation, &validationEnabled);
    try {
        if (validationEnabled) {
            auto createMessenger = reinterpret_cast<PFN_vkCreateDebugUtilsMessengerEXT>(
                vkGetInstanceProcAddr(instance, "vkCreateDebugUtilsMessengerEXT"));
            VkDebugUtilsMessengerCreateInfoEXT m{VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT};
            m.messageSeverity = VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT;
            m.messageType = VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT;
            m.pfnUserCallback = onDebugMessage;
            m.pUserData = this;
            if (createMessenger) VK_CHECK(createMessenger(instance, &m, nullptr, &messenger_));
        }
        auto devices = describeDevices(instance);
        if (devices.empty())
            throwUserError("no Vulkan device found; install mesa-vulkan-drivers (lavapipe) or a GPU driver");
        info = devices[pickDevice(devices, options.device)];
        physicalDevice = info.handle;
        vkGetPhysicalDeviceProperties(physicalDevice, &properties);
        vkGetPhysicalDeviceMemoryProperties(physicalDevice, &memoryProperties);
        if (properties.apiVersion < VK_API_VERSION_1_3)
            throwUserError("Vulkan device '" + info.name + "' supports only Vulkan " +
                           std::to_string(VK_API_VERSION_MAJOR(properties.apiVersion)) + "." +
                           std::to_string(VK_API_VERSION_MINOR(properties.apiVersion)) +
                           "; gbufferlab needs 1.3 (update the driver, or use --device cpu)");

        uint32_t familyCount = 0;
        vkGetPhysicalDeviceQueueFamilyProperties(physicalDevice, &familyCount, nullptr);
        std::vector<VkQueueFamilyProperties> families(familyCount);
        vkGetPhysicalDeviceQueueFamilyProperties(physicalDevice, &familyCount, families.data());
        queueFamily = UINT32_MAX;
        for (uint32_t i = 0; i < familyCount; ++i)
            if ((families[i].queueFlags & VK_QUEUE_GRAPHICS_BIT) && (families[i].queueFlags & VK_QUEUE_COMPUTE_BIT)) {
                queueFamily = i;
                break;
            }
        if (queueFamily == UINT32_MAX) throwUserError("Vulkan device '" + info.name + "' has no graphics+compute queue");

        float priority = 1.0f;
        VkDeviceQueueCreateInfo q{VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO};
        q.queueFamilyIndex = queueFamily;
        q.queueCount = 1;
        q.pQueuePriorities = &priority;

        VkPhysicalDeviceVulkan13Features f13{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES};
        f13.dynamicRendering = VK_TRUE;
        f13.synchronization2 = VK_TRUE;
        VkPhysicalDeviceVulkan12Features f12{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES, &f13};
        f12.hostQueryReset = VK_TRUE;
        f12.scalarBlockLayout = VK_TRUE;
        VkPhysicalDeviceFeatures2 features{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2, &f12};
        VkPhysicalDeviceFeatures supported{};
        vkGetPhysicalDeviceFeatures(physicalDevice, &supported);
        features.features.samplerAnisotropy = supported.samplerAnisotropy;
        features.features.shaderStorageImageWriteWithoutFormat = supported.shaderStorageImageWriteWithoutFormat;
        // The visibility buffer's (VulkanContext::primitiveIdInFragment, nonUniformSampledImageIndexing).
        VkPhysicalDeviceVulkan12Features supported12{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES};
        VkPhysicalDeviceFeatures2 supported2{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2, &supported12};
        vkGetPhysicalDeviceFeatures2(physicalDevice, &supported2);
        features.features.geometryShader = supported.geometryShader;
        f12.shaderSampledImageArrayNonUniformIndexing = supported12.shaderSampledImageArrayNonUniformIndexing;
        primitiveIdInFragment = supported.geometryShader == VK_TRUE;
        nonUniformSampledImageIndexing = supported12.shaderSampledImageArrayNonUniformIndexing == VK_TRUE;
        // The GPU evaluation (src/evaluate/) sums in double and indexes arrays of storage buffers
        // and images with push-constant (dynamically uniform) indices.
        features.features.shaderFloat64 = supported.shaderFloat64;
        features.features.shaderStorageBufferArrayDynamicIndexing = supported.shaderStorageBufferArrayDynamicIndexing;
        features.features.shaderStorageImageArrayDynamicIndexing = supported.shaderStorageImageArrayDynamicIndexing;
        shaderFloat64 = supported.shaderFloat64 == VK_TRUE;

        VkDeviceCreateInfo d{VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO, &features};
        d.queueCreateInfoCount = 1;
        d.pQueueCreateInfos = &q;
        VK_CHECK(vkCreateDevice(physicalDevice, &d, nullptr, &device));
        vkGetDeviceQueue(device, queueFamily, 0, &queue);

        VkCommandPoolCreateInfo pool{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
        pool.flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;
        pool.queueFamilyIndex = queueFamily;
        VK_CHECK(vkCreateCommandPool(device, &pool, nullptr, &commandPool));
        pipelineCache_.open(device, properties);
        recycler.enable(device, info.type != VK_PHYSICAL_DEVICE_TYPE_CPU);
    } catch (...) {
        release();
        throw;
    }
}

VulkanContext::~VulkanContext() { release(); }

void VulkanContext::release() noexcept {
    if (device) {
        vkDeviceWaitIdle(device);
        recycler.clear();
        pipelineCache_.save();
        pipelineCache_.destroy();
        if (commandPool) vkDestroyCommandPool(device, commandPool, nullptr);
        vkDestroyDevice(device, nullptr);
        device = VK_NULL_HANDLE;
        commandPool = VK_NULL_HANDLE;
    }
    if (messenger_) {
        auto destroyMessenger = reinterpret_cast<PFN_vkDestroyDebugUtilsMessengerEXT>(
            vkGetInstanceProcAddr(instance, "vkDestroyDebugUtilsMessengerEXT"));
        if (destroyMessenger) destroyMessenger(instance, messenger_, nullptr);
        messenger_ = VK_NULL_HANDLE;
    }
    if (instance) {
        vkDestroyInstance(instance, nullptr);
        instance = VK_NULL_HANDLE;
    }
}

void VulkanContext::noteValidationError(const char* message) {
    std::lock_guard<std::mutex> lock(messageMutex_);
    if (validationErrors_.fetch_add(1) == 0) firstValidationError_ = message;
}

std::string VulkanContext::firstValidationError() const {
    std::lock_guard<std::mutex> lock(messageMutex_);
    return firstValidationError_;
}

void VulkanContext::submitAndWait(const std::function<void(VkCommandBuffer)>& record) const {
    std::unique_lock lock(submitMutex_);
    VkCommandBufferAllocateInfo alloc{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
    alloc.commandPool = commandPool;
    alloc.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
    alloc.commandBufferCount = 1;
    VkCommandBuffer cmd;
    VK_CHECK(vkAllocateCommandBuffers(device, &alloc, &cmd));
    VkCommandBufferBeginInfo begin{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
    begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
    VK_CHECK(vkBeginCommandBuffer(cmd, &begin));
    record(cmd);
    VK_CHECK(vkEndCommandBuffer(cmd));
    VkFenceCreateInfo fenceInfo{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
    VkFence fence;
    VK_CHECK(vkCreateFence(device, &fenceInfo, nullptr, &fence));
    VkSubmitInfo submit{VK_STRUCTURE_TYPE_SUBMIT_INFO};
    submit.commandBufferCount = 1;
    submit.pCommandBuffers = &cmd;
    VK_CHECK(vkQueueSubmit(queue, 1, &submit, fence));
    lock.unlock();
    VK_CHECK(vkWaitForFences(device, 1, &fence, VK_TRUE, UINT64_MAX));
    vkDestroyFence(device, fence, nullptr);
    lock.lock();
    vkFreeCommandBuffers(device, commandPool, 1, &cmd);
}

uint32_t VulkanContext::findMemoryType(uint32_t typeBits, VkMemoryPropertyFlags required,
                                       VkMemoryPropertyFlags preferred) const {
    for (int pass = 0; pass < 2; ++pass) {
        const VkMemoryPropertyFlags want = pass == 0 ? (required | preferred) : required;
        for (uint32_t i = 0; i < memoryProperties.memoryTypeCount; ++i)
            if ((typeBits & (1u << i)) && (memoryProperties.memoryTypes[i].propertyFlags & want) == want) return i;
    }
    throw std::runtime_error("no Vulkan memory type with the required properties");
}

bool VulkanContext::isFormatSupported(VkFormat format, VkFormatFeatureFlags features) const {
    VkFormatProperties props;
    vkGetPhysicalDeviceFormatProperties(physicalDevice, format, &props);
    return (props.optimalTilingFeatures & features) == features;
}

}  // namespace gbl
