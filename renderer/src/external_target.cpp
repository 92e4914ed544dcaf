#include "vt/renderer/external_target.hpp"

#include "gpu.hpp"
#include "vt/core/error.hpp"

namespace vt::renderer {

ExternalTarget::ExternalTarget(std::shared_ptr<Device> device, const ExternalImages& images)
    : m_device(std::move(device)), m_desc(images) {
  if (m_desc.images.empty()) fail("external target: no images");
  if (m_desc.extent.width == 0 || m_desc.extent.height == 0) fail("external target: zero extent");
  if (m_desc.layers < 1 || m_desc.layers > 2) fail("external target: ", m_desc.layers, " layers (expected 1 or 2)");
  for (VkImage image : m_desc.images) {
    if (!image) fail("external target: a null image handle");
    m_views.push_back(createView(m_device->device(), image, m_desc.format, VK_IMAGE_ASPECT_COLOR_BIT, m_desc.layers, 1, true));
  }
}

ExternalTarget::~ExternalTarget() {
  // Frames drawn into these views may still run; the images themselves belong to the owner.
  vkQueueWaitIdle(m_device->queue());
  for (VkImageView view : m_views) vkDestroyImageView(m_device->device(), view, nullptr);
}

void ExternalTarget::setCurrentImage(std::uint32_t index) {
  if (index >= m_desc.images.size()) fail("external target: image ", index, " of ", m_desc.images.size());
  m_current = index;
}

bool ExternalTarget::acquire(std::uint32_t, AcquiredImage& out) {
  out = {};
  out.index = m_current;
  return true;
}

}  // namespace vt::renderer
