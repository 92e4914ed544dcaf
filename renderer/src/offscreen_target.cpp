#include "vt/renderer/offscreen_target.hpp"

#include "gpu.hpp"
#include "vt/core/error.hpp"
#include "vt/renderer/readback.hpp"
#include "vt/renderer/vk_check.hpp"

namespace vt::renderer {

struct OffscreenTarget::Slot {
  GpuImage color;
};

OffscreenTarget::OffscreenTarget(std::shared_ptr<Device> device, std::uint32_t width, std::uint32_t height,
                                 std::uint32_t layers)
    : m_device(std::move(device)), m_extent{width, height}, m_layers(layers) {
  if (width == 0 || height == 0 || width > 16384 || height > 16384) {
    fail("offscreen target: size ", width, "x", height, " out of range 1..16384");
  }
  if (layers < 1 || layers > 2) fail("offscreen target: ", layers, " layers (expected 1 or 2 views)");
  m_slots = std::make_unique<Slot[]>(kImages);
  for (std::uint32_t i = 0; i < kImages; ++i) {
    ImageSpec spec;
    spec.format = colorFormat();
    spec.extent = m_extent;
    spec.layers = layers;
    spec.usage = VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
    m_slots[i].color = GpuImage(*m_device, spec, true);
  }
}

OffscreenTarget::~OffscreenTarget() {
  // The renderer may still be drawing into these images.
  if (m_device) vkQueueWaitIdle(m_device->queue());
}

VkImageView OffscreenTarget::imageView(std::uint32_t i) const { return m_slots[i].color.view; }
VkImage OffscreenTarget::image(std::uint32_t i) const { return m_slots[i].color.image; }

bool OffscreenTarget::acquire(std::uint32_t, AcquiredImage& out) {
  out = {};
  out.index = m_next;
  m_next = (m_next + 1) % kImages;
  return true;
}

void OffscreenTarget::submitted(const AcquiredImage& image, VkFence) { m_last = int(image.index); }

Image8 OffscreenTarget::readback(std::uint32_t layer) {
  if (m_last < 0) fail("offscreen target: readback before any frame was rendered");
  if (layer >= m_layers) fail("offscreen target: layer ", layer, " of ", m_layers);
  // Frames copy nothing: only the layer asked for is copied, here. Waiting for the queue (not the
  // renderer's frame fence) keeps readback valid even after the renderer is gone.
  VT_VK(vkQueueWaitIdle(m_device->queue()));
  return readImage(*m_device, m_slots[m_last].color.image, colorFormat(), m_extent, layer, finalLayout());
}

}  // namespace vt::renderer
