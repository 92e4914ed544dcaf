// Frame capture: at xrEndFrame the app's rendering is already submitted to its queue, so a
// copy submitted after it on the same queue (with a barrier) sees the finished image.
#include "frame_capture.hpp"

#include <cstdio>
#include <cstring>

#include "api.hpp"
#include "vt/scene/image.hpp"
#include "vulkan.hpp"

namespace xrsim {

FrameCapture::FrameCapture(Session& session, std::filesystem::path outputDir)
    : m_session(session), m_dir(std::move(outputDir)) {}

FrameCapture::~FrameCapture() { release(); }

void FrameCapture::release() noexcept {
  if (m_buffer != VK_NULL_HANDLE) vkDestroyBuffer(m_session.device, m_buffer, nullptr);
  if (m_memory != VK_NULL_HANDLE) vkFreeMemory(m_session.device, m_memory, nullptr);
  m_buffer = VK_NULL_HANDLE;
  m_memory = VK_NULL_HANDLE;
  m_size = 0;
}

void FrameCapture::ensureBuffer(VkDeviceSize size) {
  if (size <= m_size) return;
  release();
  VkBufferCreateInfo info{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
  info.size = size;
  info.usage = VK_BUFFER_USAGE_TRANSFER_DST_BIT;
  info.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
  vkCheck(vkCreateBuffer(m_session.device, &info, nullptr, &m_buffer), "vkCreateBuffer");
  VkMemoryRequirements req{};
  vkGetBufferMemoryRequirements(m_session.device, m_buffer, &req);
  VkMemoryAllocateInfo alloc{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
  alloc.allocationSize = req.size;
  alloc.memoryTypeIndex = findMemoryType(m_session.physicalDevice, req.memoryTypeBits,
                                         VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT);
  vkCheck(vkAllocateMemory(m_session.device, &alloc, nullptr, &m_memory), "vkAllocateMemory");
  vkCheck(vkBindBufferMemory(m_session.device, m_buffer, m_memory, 0), "vkBindBufferMemory");
  m_size = size;
}

void FrameCapture::save(const XrCompositionLayerProjectionView& view, std::uint64_t frame, const char* eye) {
  Swapchain* swapchain = lookup<Swapchain>(view.subImage.swapchain);
  if (swapchain == nullptr || swapchain->lastReleased < 0 || (swapchain->aspect & VK_IMAGE_ASPECT_COLOR_BIT) == 0) return;
  const VkFormat format = swapchain->format;
  const bool bgra = format == VK_FORMAT_B8G8R8A8_SRGB || format == VK_FORMAT_B8G8R8A8_UNORM;
  const bool rgba = format == VK_FORMAT_R8G8B8A8_SRGB || format == VK_FORMAT_R8G8B8A8_UNORM;
  if (!bgra && !rgba) {
    vt::log::warn("xrsim: frame capture skips swapchain format ", int(format), " (only 8-bit RGBA/BGRA)");
    return;
  }
  const XrRect2Di rect = view.subImage.imageRect;
  const VkImage image = swapchain->images[std::size_t(swapchain->lastReleased)];
  ensureBuffer(VkDeviceSize(rect.extent.width) * rect.extent.height * 4);

  VkImageMemoryBarrier barrier{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER};
  barrier.srcQueueFamilyIndex = barrier.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
  barrier.image = image;
  barrier.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, view.subImage.imageArrayIndex, 1};
  m_session.commands->submitAndWait([&](VkCommandBuffer cmd) {
    barrier.srcAccessMask = VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT;
    barrier.dstAccessMask = VK_ACCESS_TRANSFER_READ_BIT;
    barrier.oldLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
    barrier.newLayout = VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL;
    vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT, 0, 0,
                         nullptr, 0, nullptr, 1, &barrier);
    VkBufferImageCopy region{};
    region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, view.subImage.imageArrayIndex, 1};
    region.imageOffset = {rect.offset.x, rect.offset.y, 0};
    region.imageExtent = {std::uint32_t(rect.extent.width), std::uint32_t(rect.extent.height), 1};
    vkCmdCopyImageToBuffer(cmd, image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, m_buffer, 1, &region);
    barrier.srcAccessMask = VK_ACCESS_TRANSFER_READ_BIT;
    barrier.dstAccessMask = VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT;
    barrier.oldLayout = VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL;
    barrier.newLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
    vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT, 0, 0,
                         nullptr, 0, nullptr, 1, &barrier);
  });

  vt::Image8 out(rect.extent.width, rect.extent.height, 4);
  void* mapped = nullptr;
  vkCheck(vkMapMemory(m_session.device, m_memory, 0, VK_WHOLE_SIZE, 0, &mapped), "vkMapMemory");
  std::memcpy(out.pixels.data(), mapped, out.pixels.size());
  vkUnmapMemory(m_session.device, m_memory);
  for (std::size_t i = 0; i < out.pixels.size(); i += 4) {
    if (bgra) std::swap(out.pixels[i], out.pixels[i + 2]);
    out.pixels[i + 3] = 255;  // the compositor ignores alpha in opaque blend mode
  }
  char name[64];
  std::snprintf(name, sizeof(name), "frame_%06llu_%s.png", static_cast<unsigned long long>(frame), eye);
  vt::savePng(m_dir / name, out);
}

}  // namespace xrsim
