#pragma once
// Copies any colour (or depth) image layer back to the CPU (screenshots of a window or an XR swapchain image,
// tests). Slow path: waits for the queue. Main thread only.
#include <vulkan/vulkan.h>

#include "vt/renderer/device.hpp"
#include "vt/scene/image.hpp"

namespace vt::renderer {

/// One layer of an 8-bit RGBA or BGRA image (returned as RGBA), currently in `layout`, which it
/// is left in again. Needs TRANSFER_SRC usage on the image. Throws vt::Error for other formats.
Image8 readImage(const Device& device, VkImage image, VkFormat format, VkExtent2D extent, std::uint32_t layer,
                 VkImageLayout layout);

/// One layer of a D32_SFLOAT, D24_UNORM_S8_UINT or D16_UNORM image as window depth in [0,1] (one
/// channel), currently in `layout`, which it is left in again. Needs TRANSFER_SRC usage.
/// Throws vt::Error for other formats.
ImageF readDepth(const Device& device, VkImage image, VkFormat format, VkExtent2D extent, std::uint32_t layer,
                 VkImageLayout layout);

}  // namespace vt::renderer
