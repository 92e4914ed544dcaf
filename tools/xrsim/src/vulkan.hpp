#pragma once
// Vulkan work the runtime does on the application's device: swapchain images, their layout
// transitions, and one-shot command submissions on the application's queue.
#include <functional>
#include <vector>

#include "objects.hpp"

namespace xrsim {

/// Throws vt::Error naming the call when a Vulkan result is a failure.
void vkCheck(VkResult result, const char* call);

/// A command pool, buffer and fence on the session's queue family; submitAndWait records,
/// submits to the session's queue and blocks until the GPU is done (the app's queue, used
/// only inside entry points, as XR_KHR_vulkan_enable2 allows).
class Commands {
 public:
  explicit Commands(const Session& session);
  ~Commands();
  Commands(const Commands&) = delete;
  Commands& operator=(const Commands&) = delete;
  void submitAndWait(const std::function<void(VkCommandBuffer)>& record);

 private:
  VkDevice m_device;
  VkQueue m_queue;
  VkCommandPool m_pool = VK_NULL_HANDLE;
  VkCommandBuffer m_buffer = VK_NULL_HANDLE;
  VkFence m_fence = VK_NULL_HANDLE;
};

/// Colour formats first (sRGB preferred), then depth formats, that the device can render to.
std::vector<VkFormat> supportedFormats(VkPhysicalDevice device);
bool isDepthFormat(VkFormat format) noexcept;

/// Creates the swapchain's images on the app's device, in the layout the spec requires at acquire.
void createSwapchainImages(Session& session, Swapchain& swapchain);

/// A memory type index with the wanted properties, or throws.
std::uint32_t findMemoryType(VkPhysicalDevice device, std::uint32_t typeBits, VkMemoryPropertyFlags wanted);

/// The layout images of this swapchain are in whenever the application does not own them.
VkImageLayout restingLayout(const Swapchain& swapchain) noexcept;

}  // namespace xrsim
