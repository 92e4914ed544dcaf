#include "vt/renderer/offscreen_target.hpp"

#include <cstring>

#include "gpu.hpp"
#include "vt/core/error.hpp"
#include "vt/renderer/vk_check.hpp"

namespace vt::renderer {

struct OffscreenTarget::Slot {
  GpuImage color;
  GpuBuffer readback;  // all layers, tightly packed RGBA8
};

OffscreenTarget::OffscreenTarget(std::shared_ptr<Device> device, std::uint32_t width, std::uint32_t height,
                                 std::uint32_t layers)
    : m_device(std::move(device)), m_extent{width, height}, m_layers(layers) {
  if (width == 0 || height == 0 || width > 16384 || height > 16384) {
    fail("offscreen target: size ", width, "x", height, " out of range 1..16384");
  }
  if (layers < 1 || layers > 2) fail("offscreen target: ", layers, " layers (expected 1 or 2 views)");
  m_slots = std::make_unique<Slot[]>(kImages);
  const VkDeviceSize bytes = VkDeviceSize(width) * height * 4 * layers;
  for (std::uint32_t i = 0; i < kImages; ++i) {
    ImageSpec spec;
    spec.format = colorFormat();
    spec.extent = m_extent;
    spec.layers = layers;
    spec.usage = VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
    m_slots[i].color = GpuImage(*m_device, spec, true);
    m_slots[i].readback = GpuBuffer(*m_device, bytes, VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                                    VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT);
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

void OffscreenTarget::recordAfterPass(VkCommandBuffer cmd, std::uint32_t imageIndex) {
  // The render pass left the image in TRANSFER_SRC and its outgoing dependency covers this copy.
  VkBufferImageCopy copy{};
  copy.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, m_layers};
  copy.imageExtent = {m_extent.width, m_extent.height, 1};
  vkCmdCopyImageToBuffer(cmd, m_slots[imageIndex].color.image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                         m_slots[imageIndex].readback.buffer, 1, &copy);
  VkBufferMemoryBarrier barrier{VK_STRUCTURE_TYPE_BUFFER_MEMORY_BARRIER};
  barrier.srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
  barrier.dstAccessMask = VK_ACCESS_HOST_READ_BIT;
  barrier.srcQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
  barrier.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
  barrier.buffer = m_slots[imageIndex].readback.buffer;
  barrier.size = VK_WHOLE_SIZE;
  vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_HOST_BIT, 0, 0, nullptr, 1, &barrier, 0,
                       nullptr);
}

void OffscreenTarget::submitted(const AcquiredImage& image, VkFence) { m_last = int(image.index); }

Image8 OffscreenTarget::readback(std::uint32_t layer) {
  if (m_last < 0) fail("offscreen target: readback before any frame was rendered");
  if (layer >= m_layers) fail("offscreen target: layer ", layer, " of ", m_layers);
  // Waiting for the queue (not the renderer's frame fence) keeps readback valid even after the
  // renderer is gone; readback is a slow path anyway.
  VT_VK(vkQueueWaitIdle(m_device->queue()));
  Image8 out(int(m_extent.width), int(m_extent.height), 4);
  const std::size_t layerBytes = out.pixels.size();
  std::memcpy(out.pixels.data(), static_cast<const std::uint8_t*>(m_slots[m_last].readback.mapped) + layerBytes * layer,
              layerBytes);
  return out;
}

}  // namespace vt::renderer
