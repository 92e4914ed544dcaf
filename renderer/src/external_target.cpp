#include "vt/renderer/external_target.hpp"

#include "gpu.hpp"
#include "vt/core/error.hpp"

namespace vt::renderer {

bool supportsExternalDepth(const Device& device, VkFormat format) {
  if (format != VK_FORMAT_D32_SFLOAT && format != VK_FORMAT_D24_UNORM_S8_UINT && format != VK_FORMAT_D16_UNORM) {
    return false;
  }
  VkFormatProperties props{};
  vkGetPhysicalDeviceFormatProperties(device.physicalDevice(), format, &props);
  return (props.optimalTilingFeatures & VK_FORMAT_FEATURE_DEPTH_STENCIL_ATTACHMENT_BIT) != 0;
}

ExternalTarget::ExternalTarget(std::shared_ptr<Device> device, const ExternalImages& images)
    : m_device(std::move(device)), m_desc(images) {
  if (m_desc.images.empty()) fail("external target: no images");
  if (m_desc.extent.width == 0 || m_desc.extent.height == 0) fail("external target: zero extent");
  if (m_desc.layers < 1 || m_desc.layers > 2) fail("external target: ", m_desc.layers, " layers (expected 1 or 2)");
  for (VkImage image : m_desc.images) {
    if (!image) fail("external target: a null image handle");
  }
  for (VkImage image : m_desc.depthImages) {
    if (!image) fail("external target: a null depth image handle");
  }
  if (!m_desc.depthImages.empty() && !supportsExternalDepth(*m_device, m_desc.depthFormat)) {
    fail("external target: depth format ", int(m_desc.depthFormat), " is not usable as a depth attachment");
  }
  // Checks first, so a bad description leaks no views.
  for (VkImage image : m_desc.images) {
    m_views.push_back(createView(m_device->device(), image, m_desc.format, VK_IMAGE_ASPECT_COLOR_BIT, m_desc.layers, 1, true));
  }
  for (VkImage image : m_desc.depthImages) {
    m_depthViews.push_back(createView(m_device->device(), image, m_desc.depthFormat, depthAspectOf(m_desc.depthFormat),
                                      m_desc.layers, 1, true));
  }
}

ExternalTarget::~ExternalTarget() {
  // Frames drawn into these views may still run; the images themselves belong to the owner.
  vkQueueWaitIdle(m_device->queue());
  for (VkImageView view : m_views) vkDestroyImageView(m_device->device(), view, nullptr);
  for (VkImageView view : m_depthViews) vkDestroyImageView(m_device->device(), view, nullptr);
}

void ExternalTarget::setCurrentImage(std::uint32_t index) {
  if (index >= m_desc.images.size()) fail("external target: image ", index, " of ", m_desc.images.size());
  m_current = index;
}

void ExternalTarget::setCurrentDepthImage(std::uint32_t index) {
  if (index >= m_desc.depthImages.size()) {
    fail("external target: depth image ", index, " of ", m_desc.depthImages.size());
  }
  m_currentDepth = index;
}

bool ExternalTarget::acquire(std::uint32_t, AcquiredImage& out) {
  out = {};
  out.index = m_current;
  out.depthIndex = m_currentDepth;
  return true;
}

}  // namespace vt::renderer
