// XR_KHR_vulkan_enable2 and the runtime's own Vulkan work on the application's device.
#include "vulkan.hpp"

#include <algorithm>
#include <cstring>

#include "api.hpp"

namespace xrsim {

void vkCheck(VkResult result, const char* call) {
  if (result < 0) vt::fail(call, " failed with VkResult ", int(result));
}

Commands::Commands(const Session& session) : m_device(session.device), m_queue(session.queue) {
  VkCommandPoolCreateInfo poolInfo{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
  poolInfo.flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;
  poolInfo.queueFamilyIndex = session.queueFamily;
  vkCheck(vkCreateCommandPool(m_device, &poolInfo, nullptr, &m_pool), "vkCreateCommandPool");
  VkCommandBufferAllocateInfo allocInfo{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
  allocInfo.commandPool = m_pool;
  allocInfo.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
  allocInfo.commandBufferCount = 1;
  vkCheck(vkAllocateCommandBuffers(m_device, &allocInfo, &m_buffer), "vkAllocateCommandBuffers");
  VkFenceCreateInfo fenceInfo{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
  vkCheck(vkCreateFence(m_device, &fenceInfo, nullptr, &m_fence), "vkCreateFence");
}

Commands::~Commands() {
  vkDestroyFence(m_device, m_fence, nullptr);
  vkDestroyCommandPool(m_device, m_pool, nullptr);
}

void Commands::submitAndWait(const std::function<void(VkCommandBuffer)>& record) {
  vkCheck(vkResetCommandBuffer(m_buffer, 0), "vkResetCommandBuffer");
  VkCommandBufferBeginInfo begin{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
  begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
  vkCheck(vkBeginCommandBuffer(m_buffer, &begin), "vkBeginCommandBuffer");
  record(m_buffer);
  vkCheck(vkEndCommandBuffer(m_buffer), "vkEndCommandBuffer");
  VkSubmitInfo submit{VK_STRUCTURE_TYPE_SUBMIT_INFO};
  submit.commandBufferCount = 1;
  submit.pCommandBuffers = &m_buffer;
  vkCheck(vkQueueSubmit(m_queue, 1, &submit, m_fence), "vkQueueSubmit");
  vkCheck(vkWaitForFences(m_device, 1, &m_fence, VK_TRUE, UINT64_MAX), "vkWaitForFences");
  vkCheck(vkResetFences(m_device, 1, &m_fence), "vkResetFences");
}

bool isDepthFormat(VkFormat format) noexcept {
  return format == VK_FORMAT_D32_SFLOAT || format == VK_FORMAT_D24_UNORM_S8_UINT || format == VK_FORMAT_D16_UNORM ||
         format == VK_FORMAT_D32_SFLOAT_S8_UINT;
}

std::vector<VkFormat> supportedFormats(VkPhysicalDevice device) {
  const VkFormat colour[] = {VK_FORMAT_R8G8B8A8_SRGB, VK_FORMAT_B8G8R8A8_SRGB, VK_FORMAT_R8G8B8A8_UNORM,
                             VK_FORMAT_B8G8R8A8_UNORM, VK_FORMAT_R16G16B16A16_SFLOAT};
  const VkFormat depth[] = {VK_FORMAT_D32_SFLOAT, VK_FORMAT_D24_UNORM_S8_UINT, VK_FORMAT_D16_UNORM};
  std::vector<VkFormat> out;
  for (VkFormat f : colour) {
    VkFormatProperties props{};
    vkGetPhysicalDeviceFormatProperties(device, f, &props);
    const VkFormatFeatureFlags need = VK_FORMAT_FEATURE_COLOR_ATTACHMENT_BIT | VK_FORMAT_FEATURE_TRANSFER_SRC_BIT;
    if ((props.optimalTilingFeatures & need) == need) out.push_back(f);
  }
  for (VkFormat f : depth) {
    VkFormatProperties props{};
    vkGetPhysicalDeviceFormatProperties(device, f, &props);
    const VkFormatFeatureFlags need = VK_FORMAT_FEATURE_DEPTH_STENCIL_ATTACHMENT_BIT | VK_FORMAT_FEATURE_TRANSFER_SRC_BIT;
    if ((props.optimalTilingFeatures & need) == need) out.push_back(f);
  }
  return out;
}

std::uint32_t findMemoryType(VkPhysicalDevice device, std::uint32_t typeBits, VkMemoryPropertyFlags wanted) {
  VkPhysicalDeviceMemoryProperties props{};
  vkGetPhysicalDeviceMemoryProperties(device, &props);
  for (std::uint32_t i = 0; i < props.memoryTypeCount; ++i)
    if ((typeBits & (1u << i)) && (props.memoryTypes[i].propertyFlags & wanted) == wanted) return i;
  vt::fail("no Vulkan memory type with properties 0x", std::hex, wanted, " for bits 0x", typeBits);
}

VkImageLayout restingLayout(const Swapchain& swapchain) noexcept {
  return (swapchain.aspect & VK_IMAGE_ASPECT_DEPTH_BIT) ? VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL
                                                        : VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
}

void createSwapchainImages(Session& session, Swapchain& swapchain) {
  const XrSwapchainCreateInfo& info = swapchain.info;
  const bool depth = isDepthFormat(swapchain.format);
  swapchain.aspect = depth ? VK_IMAGE_ASPECT_DEPTH_BIT : VK_IMAGE_ASPECT_COLOR_BIT;
  if (swapchain.format == VK_FORMAT_D24_UNORM_S8_UINT || swapchain.format == VK_FORMAT_D32_SFLOAT_S8_UINT)
    swapchain.aspect |= VK_IMAGE_ASPECT_STENCIL_BIT;

  VkImageUsageFlags usage = 0;
  if (info.usageFlags & XR_SWAPCHAIN_USAGE_SAMPLED_BIT) usage |= VK_IMAGE_USAGE_SAMPLED_BIT;
  if (info.usageFlags & XR_SWAPCHAIN_USAGE_UNORDERED_ACCESS_BIT) usage |= VK_IMAGE_USAGE_STORAGE_BIT;
  if (info.usageFlags & XR_SWAPCHAIN_USAGE_TRANSFER_DST_BIT) usage |= VK_IMAGE_USAGE_TRANSFER_DST_BIT;
  if (info.usageFlags & XR_SWAPCHAIN_USAGE_INPUT_ATTACHMENT_BIT_KHR) usage |= VK_IMAGE_USAGE_INPUT_ATTACHMENT_BIT;
  // The runtime always renders-to (layout contract) and reads back (capture) its images.
  usage |= (depth ? VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT : VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT) |
           VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
  usage |= VK_IMAGE_USAGE_TRANSFER_SRC_BIT;

  VkImageCreateInfo imageInfo{VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO};
  imageInfo.flags = (info.usageFlags & XR_SWAPCHAIN_USAGE_MUTABLE_FORMAT_BIT) ? VK_IMAGE_CREATE_MUTABLE_FORMAT_BIT : 0;
  imageInfo.imageType = VK_IMAGE_TYPE_2D;
  imageInfo.format = swapchain.format;
  imageInfo.extent = {info.width, info.height, 1};
  imageInfo.mipLevels = info.mipCount;
  imageInfo.arrayLayers = info.arraySize;
  imageInfo.samples = VkSampleCountFlagBits(info.sampleCount);
  imageInfo.tiling = VK_IMAGE_TILING_OPTIMAL;
  imageInfo.usage = usage;
  imageInfo.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
  imageInfo.initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;

  const std::uint32_t imageCount = (info.createFlags & XR_SWAPCHAIN_CREATE_STATIC_IMAGE_BIT) ? 1 : 3;
  for (std::uint32_t i = 0; i < imageCount; ++i) {
    VkImage image = VK_NULL_HANDLE;
    vkCheck(vkCreateImage(session.device, &imageInfo, nullptr, &image), "vkCreateImage");
    swapchain.images.push_back(image);
    VkMemoryRequirements req{};
    vkGetImageMemoryRequirements(session.device, image, &req);
    VkMemoryAllocateInfo alloc{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
    alloc.allocationSize = req.size;
    alloc.memoryTypeIndex = findMemoryType(session.physicalDevice, req.memoryTypeBits, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT);
    VkDeviceMemory memory = VK_NULL_HANDLE;
    vkCheck(vkAllocateMemory(session.device, &alloc, nullptr, &memory), "vkAllocateMemory");
    swapchain.memory.push_back(memory);
    vkCheck(vkBindImageMemory(session.device, image, memory, 0), "vkBindImageMemory");
  }

  // XR_KHR_vulkan_enable: acquired images are in COLOR_ATTACHMENT_OPTIMAL (colour) or
  // DEPTH_STENCIL_ATTACHMENT_OPTIMAL (depth), so transition them once now.
  const VkImageLayout layout = restingLayout(swapchain);
  session.commands->submitAndWait([&](VkCommandBuffer cmd) {
    std::vector<VkImageMemoryBarrier> barriers;
    for (VkImage image : swapchain.images) {
      VkImageMemoryBarrier barrier{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER};
      barrier.srcAccessMask = 0;
      barrier.dstAccessMask = depth ? VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT : VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT;
      barrier.oldLayout = VK_IMAGE_LAYOUT_UNDEFINED;
      barrier.newLayout = layout;
      barrier.srcQueueFamilyIndex = barrier.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
      barrier.image = image;
      barrier.subresourceRange = {swapchain.aspect, 0, info.mipCount, 0, info.arraySize};
      barriers.push_back(barrier);
    }
    vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, VK_PIPELINE_STAGE_ALL_COMMANDS_BIT, 0, 0, nullptr, 0,
                         nullptr, std::uint32_t(barriers.size()), barriers.data());
  });
}

Swapchain::~Swapchain() {
  if (session == nullptr) return;
  // The app must not use the images any more; make sure our own transfers are done too.
  vkDeviceWaitIdle(session->device);
  for (VkImage image : images) vkDestroyImage(session->device, image, nullptr);
  for (VkDeviceMemory m : memory) vkFreeMemory(session->device, m, nullptr);
}

// ---- XR_KHR_vulkan_enable2 entry points ----

XrResult XRAPI_CALL getVulkanGraphicsRequirements2(XrInstance handle, XrSystemId system,
                                                   XrGraphicsRequirementsVulkanKHR* requirements) {
  return guarded("xrGetVulkanGraphicsRequirements2KHR", [&]() -> XrResult {
    Instance* instance = nullptr;
    if (XrResult r = findInstance(handle, instance); r != XR_SUCCESS) return r;
    if (XrResult r = checkSystem(*instance, system); r != XR_SUCCESS) return r;
    XRSIM_CHECK_STRUCT(requirements, XR_TYPE_GRAPHICS_REQUIREMENTS_VULKAN2_KHR);
    requirements->minApiVersionSupported = XR_MAKE_VERSION(1, 0, 0);
    requirements->maxApiVersionSupported = XR_MAKE_VERSION(1, 3, 0);
    instance->requirementsQueried = true;
    return XR_SUCCESS;
  });
}

XrResult XRAPI_CALL createVulkanInstance(XrInstance handle, const XrVulkanInstanceCreateInfoKHR* info,
                                         VkInstance* vkInstance, VkResult* vkResult) {
  return guarded("xrCreateVulkanInstanceKHR", [&]() -> XrResult {
    Instance* instance = nullptr;
    if (XrResult r = findInstance(handle, instance); r != XR_SUCCESS) return r;
    XRSIM_CHECK_STRUCT(info, XR_TYPE_VULKAN_INSTANCE_CREATE_INFO_KHR);
    if (XrResult r = checkSystem(*instance, info->systemId); r != XR_SUCCESS) return r;
    if (vkInstance == nullptr || vkResult == nullptr || info->pfnGetInstanceProcAddr == nullptr ||
        info->vulkanCreateInfo == nullptr || info->createFlags != 0)
      return XR_ERROR_VALIDATION_FAILURE;
    auto create = reinterpret_cast<PFN_vkCreateInstance>(info->pfnGetInstanceProcAddr(VK_NULL_HANDLE, "vkCreateInstance"));
    if (create == nullptr) return XR_ERROR_RUNTIME_FAILURE;
    VkInstanceCreateInfo createInfo = *info->vulkanCreateInfo;
    std::vector<const char*> layers(createInfo.ppEnabledLayerNames, createInfo.ppEnabledLayerNames + createInfo.enabledLayerCount);
    const char* kValidation = "VK_LAYER_KHRONOS_validation";
    const bool hasValidation = std::any_of(layers.begin(), layers.end(), [&](const char* l) { return std::strcmp(l, kValidation) == 0; });
    if (instance->config.validation && !hasValidation) {
      layers.push_back(kValidation);
      createInfo.enabledLayerCount = std::uint32_t(layers.size());
      createInfo.ppEnabledLayerNames = layers.data();
    }
    *vkResult = create(&createInfo, info->vulkanAllocator, vkInstance);
    return XR_SUCCESS;
  });
}

XrResult XRAPI_CALL getVulkanGraphicsDevice2(XrInstance handle, const XrVulkanGraphicsDeviceGetInfoKHR* info,
                                             VkPhysicalDevice* out) {
  return guarded("xrGetVulkanGraphicsDevice2KHR", [&]() -> XrResult {
    Instance* instance = nullptr;
    if (XrResult r = findInstance(handle, instance); r != XR_SUCCESS) return r;
    XRSIM_CHECK_STRUCT(info, XR_TYPE_VULKAN_GRAPHICS_DEVICE_GET_INFO_KHR);
    if (XrResult r = checkSystem(*instance, info->systemId); r != XR_SUCCESS) return r;
    if (out == nullptr || info->vulkanInstance == VK_NULL_HANDLE) return XR_ERROR_VALIDATION_FAILURE;
    std::uint32_t count = 0;
    vkCheck(vkEnumeratePhysicalDevices(info->vulkanInstance, &count, nullptr), "vkEnumeratePhysicalDevices");
    if (count == 0) return XR_ERROR_RUNTIME_FAILURE;
    std::vector<VkPhysicalDevice> devices(count);
    vkCheck(vkEnumeratePhysicalDevices(info->vulkanInstance, &count, devices.data()), "vkEnumeratePhysicalDevices");
    // Whatever device is present (lavapipe on CI): the first one.
    instance->vkInstance = info->vulkanInstance;
    instance->physicalDevice = devices[0];
    *out = devices[0];
    return XR_SUCCESS;
  });
}

XrResult XRAPI_CALL createVulkanDevice(XrInstance handle, const XrVulkanDeviceCreateInfoKHR* info, VkDevice* vkDevice,
                                       VkResult* vkResult) {
  return guarded("xrCreateVulkanDeviceKHR", [&]() -> XrResult {
    Instance* instance = nullptr;
    if (XrResult r = findInstance(handle, instance); r != XR_SUCCESS) return r;
    XRSIM_CHECK_STRUCT(info, XR_TYPE_VULKAN_DEVICE_CREATE_INFO_KHR);
    if (XrResult r = checkSystem(*instance, info->systemId); r != XR_SUCCESS) return r;
    if (vkDevice == nullptr || vkResult == nullptr || info->pfnGetInstanceProcAddr == nullptr ||
        info->vulkanCreateInfo == nullptr || info->createFlags != 0)
      return XR_ERROR_VALIDATION_FAILURE;
    if (instance->physicalDevice == VK_NULL_HANDLE || info->vulkanPhysicalDevice != instance->physicalDevice)
      return XR_ERROR_GRAPHICS_DEVICE_INVALID;
    auto create = reinterpret_cast<PFN_vkCreateDevice>(info->pfnGetInstanceProcAddr(instance->vkInstance, "vkCreateDevice"));
    if (create == nullptr) return XR_ERROR_RUNTIME_FAILURE;
    *vkResult = create(info->vulkanPhysicalDevice, info->vulkanCreateInfo, info->vulkanAllocator, vkDevice);
    return XR_SUCCESS;
  });
}

}  // namespace xrsim
