#pragma once
// Small owning wrappers for buffers and images plus one-shot command submission (internal).
#include <cstdint>
#include <functional>

#include "vt/renderer/device.hpp"

namespace vt::renderer {

/// A buffer with its own memory; host-visible ones stay mapped.
struct GpuBuffer {
  VkDevice device = VK_NULL_HANDLE;
  VkBuffer buffer = VK_NULL_HANDLE;
  VkDeviceMemory memory = VK_NULL_HANDLE;
  VkDeviceSize size = 0;
  void* mapped = nullptr;

  GpuBuffer() = default;
  GpuBuffer(const Device& dev, VkDeviceSize bytes, VkBufferUsageFlags usage, VkMemoryPropertyFlags properties);
  GpuBuffer(GpuBuffer&& other) noexcept { *this = std::move(other); }
  GpuBuffer& operator=(GpuBuffer&& other) noexcept;
  ~GpuBuffer() { reset(); }
  void reset() noexcept;
};

/// What a GpuImage is.
struct ImageSpec {
  VkFormat format = VK_FORMAT_R8G8B8A8_SRGB;
  VkExtent2D extent{};
  std::uint32_t layers = 1;
  std::uint32_t mipLevels = 1;
  VkImageUsageFlags usage = 0;
  VkImageAspectFlags aspect = VK_IMAGE_ASPECT_COLOR_BIT;
};

/// A device-local optimal-tiling image with a 2D-array (or 2D when one layer) view of all levels.
struct GpuImage {
  VkDevice device = VK_NULL_HANDLE;
  VkImage image = VK_NULL_HANDLE;
  VkDeviceMemory memory = VK_NULL_HANDLE;
  VkImageView view = VK_NULL_HANDLE;
  ImageSpec spec;

  GpuImage() = default;
  GpuImage(const Device& dev, const ImageSpec& spec, bool arrayView);
  GpuImage(GpuImage&& other) noexcept { *this = std::move(other); }
  GpuImage& operator=(GpuImage&& other) noexcept;
  ~GpuImage() { reset(); }
  void reset() noexcept;
};

/// Creates a view of layers [baseLayer, baseLayer + layers) (2D array view when arrayView, else 2D).
VkImageView createView(VkDevice device, VkImage image, VkFormat format, VkImageAspectFlags aspect,
                       std::uint32_t layers, std::uint32_t levels, bool arrayView, std::uint32_t baseLayer = 0);

/// DEPTH, or DEPTH | STENCIL for a combined depth-stencil format (attachment views need both).
VkImageAspectFlags depthAspectOf(VkFormat format) noexcept;

/// Records commands into a fresh command buffer, submits, and waits (setup only, not per frame).
void submitOnce(const Device& dev, const std::function<void(VkCommandBuffer)>& record);

/// A full pipeline barrier for one image's layout transition (setup paths).
void transitionImage(VkCommandBuffer cmd, VkImage image, VkImageAspectFlags aspect, VkImageLayout from,
                     VkImageLayout to, std::uint32_t baseLevel, std::uint32_t levels, std::uint32_t layers);

}  // namespace vt::renderer
