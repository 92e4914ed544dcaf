#pragma once
// Vulkan instance + device: created here (discrete GPU preferred, lavapipe as fallback), created
// through hooks (OpenXR's XR_KHR_vulkan_enable2 creates instance and device itself), or adopted
// from handles someone else owns. Vulkan types appear here on purpose: this is the creation API.
#include <atomic>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include <vulkan/vulkan.h>

namespace vt::renderer {

/// Lets a runtime (OpenXR) perform the creation calls while the renderer fills the create infos.
/// Every hook is optional; an empty one uses the plain Vulkan call / the default choice.
struct DeviceCreationHooks {
  /// Instead of vkCreateInstance (e.g. xrCreateVulkanInstanceKHR). Must throw on failure.
  std::function<VkInstance(const VkInstanceCreateInfo&)> createInstance;
  /// Instead of the default choice (e.g. xrGetVulkanGraphicsDevice2KHR).
  std::function<VkPhysicalDevice(VkInstance)> pickPhysicalDevice;
  /// Instead of vkCreateDevice (e.g. xrCreateVulkanDeviceKHR). Must throw on failure.
  std::function<VkDevice(VkPhysicalDevice, const VkDeviceCreateInfo&)> createDevice;
};

/// How to create the device.
struct DeviceOptions {
  bool validate = false;                      // VK_LAYER_KHRONOS_validation + debug messages -> vt::log
  bool preferDiscrete = true;                 // else take the first device with graphics
  std::vector<std::string> instanceExtensions;  // extra, e.g. glfwGetRequiredInstanceExtensions()
  std::vector<std::string> deviceExtensions;    // extra, e.g. VK_KHR_swapchain (see addWindowExtensions)
  DeviceCreationHooks hooks;
};

/// Handles created and owned by someone else (the Device never destroys them).
struct ExternalDevice {
  VkInstance instance = VK_NULL_HANDLE;
  VkPhysicalDevice physicalDevice = VK_NULL_HANDLE;
  VkDevice device = VK_NULL_HANDLE;
  std::uint32_t queueFamily = 0;
  std::uint32_t queueIndex = 0;
  /// The device must have Vulkan 1.1 with the multiview feature enabled.
};

/// The Vulkan instance, physical device, logical device and graphics queue. Main thread only,
/// except validationMessageCount() (any thread).
class Device {
 public:
  /// Creates instance and device. Throws vt::Error when no usable device exists.
  static std::shared_ptr<Device> create(const DeviceOptions& options = {});
  /// Wraps handles owned elsewhere (no validation messenger unless the instance has debug utils).
  static std::shared_ptr<Device> adopt(const ExternalDevice& handles);
  ~Device();
  Device(const Device&) = delete;
  Device& operator=(const Device&) = delete;

  VkInstance instance() const { return m_instance; }
  VkPhysicalDevice physicalDevice() const { return m_physical; }
  VkDevice device() const { return m_device; }
  VkQueue queue() const { return m_queue; }
  std::uint32_t queueFamily() const { return m_queueFamily; }
  /// "llvmpipe (LLVM 15.0.6, 256 bits) [cpu]".
  const std::string& description() const { return m_description; }
  /// True when the chosen device is a software rasteriser (lavapipe/llvmpipe).
  bool isSoftware() const { return m_software; }
  bool validationEnabled() const { return m_messenger != VK_NULL_HANDLE; }
  /// Validation warnings+errors seen so far (tests fail when it is not zero).
  std::uint64_t validationMessageCount() const { return m_validationMessages.load(); }
  /// A memory type index with the bits and properties, or throws vt::Error.
  std::uint32_t memoryType(std::uint32_t typeBits, VkMemoryPropertyFlags properties) const;
  /// False for lavapipe, whose multiview loses clipped triangles in view 1 (seen on Mesa 22.3,
  /// newer versions not re-checked): the renderer then draws one pass per view (StereoMode).
  bool multiviewReliable() const { return m_multiviewReliable; }
  /// minUniformBufferOffsetAlignment of the device.
  VkDeviceSize uniformAlignment() const { return m_uniformAlignment; }
  /// A depth format usable as an optimal-tiling depth attachment.
  VkFormat depthFormat() const { return m_depthFormat; }
  void waitIdle() const;

 private:
  Device() = default;
  void selectPhysicalDevice(bool preferDiscrete);
  void finishSetup();

  VkInstance m_instance = VK_NULL_HANDLE;
  VkPhysicalDevice m_physical = VK_NULL_HANDLE;
  VkDevice m_device = VK_NULL_HANDLE;
  VkQueue m_queue = VK_NULL_HANDLE;
  std::uint32_t m_queueFamily = 0;
  VkDebugUtilsMessengerEXT m_messenger = VK_NULL_HANDLE;
  VkPhysicalDeviceMemoryProperties m_memory{};
  VkFormat m_depthFormat = VK_FORMAT_UNDEFINED;
  std::string m_description;
  bool m_software = false;
  bool m_multiviewReliable = true;
  VkDeviceSize m_uniformAlignment = 256;
  bool m_owned = true;
  std::atomic<std::uint64_t> m_validationMessages{0};
};

}  // namespace vt::renderer
