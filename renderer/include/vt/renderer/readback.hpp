#pragma once
// Copies any colour image layer back to the CPU (screenshots of a window or an XR swapchain image,
// tests). Slow path: waits for the queue. Main thread only.
#include <vulkan/vulkan.h>

#include "vt/renderer/device.hpp"
#include "vt/scene/image.hpp"

namespace vt::renderer {

/// One layer of an 8-bit RGBA or BGRA image (returned as RGBA), currently in `layout`, which it
/// is left in again. Needs TRANSFER_SRC usage on the image. Throws vt::Error for other formats.
Image8 readImage(const Device& device, VkImage image, VkFormat format, VkExtent2D extent, std::uint32_t layer,
                 VkImageLayout layout);

}  // namespace vt::renderer
