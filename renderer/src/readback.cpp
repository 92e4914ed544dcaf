#include "vt/renderer/readback.hpp"

#include <cstring>
#include <utility>

#include "gpu.hpp"
#include "vt/core/error.hpp"
#include "vt/renderer/vk_check.hpp"

namespace vt::renderer {
namespace {

// One layer's `copyAspect` into a host-visible buffer of `bytes`, the image back in `layout`
// after (its layouts change for every aspect in `layoutAspects`).
GpuBuffer copyLayerToHost(const Device& device, VkImage image, VkImageAspectFlags layoutAspects,
                          VkImageAspectFlags copyAspect, VkExtent2D extent, std::uint32_t layer, VkImageLayout layout,
                          VkDeviceSize bytes) {
  GpuBuffer buffer(device, bytes, VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                   VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT);
  submitOnce(device, [&](VkCommandBuffer cmd) {
    transitionImage(cmd, image, layoutAspects, layout, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, 0, 1, layer + 1);
    VkBufferImageCopy copy{};
    copy.imageSubresource = {copyAspect, 0, layer, 1};
    copy.imageExtent = {extent.width, extent.height, 1};
    vkCmdCopyImageToBuffer(cmd, image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, buffer.buffer, 1, &copy);
    transitionImage(cmd, image, layoutAspects, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, layout, 0, 1, layer + 1);
  });
  return buffer;
}

}  // namespace

Image8 readImage(const Device& device, VkImage image, VkFormat format, VkExtent2D extent, std::uint32_t layer,
                 VkImageLayout layout) {
  bool bgra = false;
  switch (format) {
    case VK_FORMAT_R8G8B8A8_SRGB:
    case VK_FORMAT_R8G8B8A8_UNORM: break;
    case VK_FORMAT_B8G8R8A8_SRGB:
    case VK_FORMAT_B8G8R8A8_UNORM: bgra = true; break;
    default: fail("readImage: unsupported format ", int(format), " (8-bit RGBA/BGRA only)");
  }
  Image8 out(int(extent.width), int(extent.height), 4);
  const GpuBuffer buffer = copyLayerToHost(device, image, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_ASPECT_COLOR_BIT, extent,
                                           layer, layout, out.pixels.size());
  std::memcpy(out.pixels.data(), buffer.mapped, out.pixels.size());
  if (bgra) {
    for (std::size_t i = 0; i < out.pixels.size(); i += 4) std::swap(out.pixels[i], out.pixels[i + 2]);
  }
  return out;
}

ImageF readDepth(const Device& device, VkImage image, VkFormat format, VkExtent2D extent, std::uint32_t layer,
                 VkImageLayout layout) {
  if (format != VK_FORMAT_D32_SFLOAT && format != VK_FORMAT_D24_UNORM_S8_UINT && format != VK_FORMAT_D16_UNORM) {
    fail("readDepth: unsupported format ", int(format), " (D32_SFLOAT, D24_UNORM_S8_UINT or D16_UNORM)");
  }
  ImageF out(int(extent.width), int(extent.height), 1);
  // The depth aspect copies tightly packed: 4 bytes (D24 in the low 24 bits) or 2 for D16.
  const std::size_t texel = format == VK_FORMAT_D16_UNORM ? 2 : 4;
  const GpuBuffer buffer = copyLayerToHost(device, image, depthAspectOf(format), VK_IMAGE_ASPECT_DEPTH_BIT, extent,
                                           layer, layout, out.pixels.size() * texel);
  const auto* bytes = static_cast<const std::uint8_t*>(buffer.mapped);
  for (std::size_t i = 0; i < out.pixels.size(); ++i) {
    if (format == VK_FORMAT_D32_SFLOAT) {
      std::memcpy(&out.pixels[i], bytes + i * 4, 4);
    } else if (format == VK_FORMAT_D16_UNORM) {
      std::uint16_t v = 0;
      std::memcpy(&v, bytes + i * 2, 2);
      out.pixels[i] = float(v) / 65535.0f;
    } else {
      std::uint32_t v = 0;
      std::memcpy(&v, bytes + i * 4, 4);
      out.pixels[i] = float(v & 0xFFFFFFu) / 16777215.0f;
    }
  }
  return out;
}

}  // namespace vt::renderer
