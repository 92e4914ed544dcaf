// Frame capture: at xrEndFrame the app's rendering is already submitted to its queue, so a
// copy submitted after it on the same queue (with a barrier) sees the finished image.
#include "frame_capture.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>

#include "api.hpp"
#include "vt/scene/image.hpp"
#include "vulkan.hpp"

namespace xrsim {
namespace {

std::string fileName(std::uint64_t frame, const char* eye, const char* suffix) {
  char name[80];
  std::snprintf(name, sizeof(name), "frame_%06llu_%s%s.png", static_cast<unsigned long long>(frame), eye, suffix);
  return name;
}

}  // namespace

FrameCapture::FrameCapture(Session& session, std::filesystem::path outputDir)
    : m_session(session), m_dir(std::move(outputDir)) {}

FrameCapture::~FrameCapture() { release(); }

void FrameCapture::release() noexcept {
  if (m_buffer != VK_NULL_HANDLE) vkDestroyBuffer(m_session.device, m_buffer, nullptr);
  if (m_memory != VK_NULL_HANDLE) vkFreeMemory(m_session.device, m_memory, nullptr);  // unmaps too
  m_buffer = VK_NULL_HANDLE;
  m_memory = VK_NULL_HANDLE;
  m_mapped = nullptr;
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
  vkCheck(vkMapMemory(m_session.device, m_memory, 0, VK_WHOLE_SIZE, 0, &m_mapped), "vkMapMemory");
  m_size = size;
}

const std::uint8_t* FrameCapture::copyReleased(const Swapchain& swapchain, const XrSwapchainSubImage& sub,
                                               VkImageAspectFlags aspect, VkDeviceSize bytes) {
  const XrRect2Di rect = sub.imageRect;
  const VkImage image = swapchain.images[std::size_t(swapchain.lastReleased)];
  const bool depth = (swapchain.aspect & VK_IMAGE_ASPECT_DEPTH_BIT) != 0;
  const VkImageLayout resting = restingLayout(swapchain);
  const VkPipelineStageFlags attachmentStage =
      depth ? VK_PIPELINE_STAGE_LATE_FRAGMENT_TESTS_BIT : VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT;
  const VkAccessFlags attachmentWrite =
      depth ? VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT : VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT;
  ensureBuffer(bytes);

  VkImageMemoryBarrier barrier{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER};
  barrier.srcQueueFamilyIndex = barrier.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
  barrier.image = image;
  barrier.subresourceRange = {swapchain.aspect, 0, 1, sub.imageArrayIndex, 1};  // layouts cover all aspects
  m_session.commands->submitAndWait([&](VkCommandBuffer cmd) {
    barrier.srcAccessMask = attachmentWrite;
    barrier.dstAccessMask = VK_ACCESS_TRANSFER_READ_BIT;
    barrier.oldLayout = resting;
    barrier.newLayout = VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL;
    vkCmdPipelineBarrier(cmd, attachmentStage, VK_PIPELINE_STAGE_TRANSFER_BIT, 0, 0, nullptr, 0, nullptr, 1, &barrier);
    VkBufferImageCopy region{};
    region.imageSubresource = {aspect, 0, sub.imageArrayIndex, 1};
    region.imageOffset = {rect.offset.x, rect.offset.y, 0};
    region.imageExtent = {std::uint32_t(rect.extent.width), std::uint32_t(rect.extent.height), 1};
    vkCmdCopyImageToBuffer(cmd, image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, m_buffer, 1, &region);
    barrier.srcAccessMask = VK_ACCESS_TRANSFER_READ_BIT;
    barrier.dstAccessMask = attachmentWrite;
    barrier.oldLayout = VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL;
    barrier.newLayout = resting;
    vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, attachmentStage, 0, 0, nullptr, 0, nullptr, 1, &barrier);
  });
  return static_cast<const std::uint8_t*>(m_mapped);
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
  vt::Image8 out(rect.extent.width, rect.extent.height, 4);
  std::memcpy(out.pixels.data(), copyReleased(*swapchain, view.subImage, VK_IMAGE_ASPECT_COLOR_BIT, out.pixels.size()),
              out.pixels.size());
  for (std::size_t i = 0; i < out.pixels.size(); i += 4) {
    if (bgra) std::swap(out.pixels[i], out.pixels[i + 2]);
    out.pixels[i + 3] = 255;  // the compositor ignores alpha in opaque blend mode
  }
  vt::savePng(m_dir / fileName(frame, eye, ""), out);
}

void FrameCapture::saveDepth(const XrCompositionLayerDepthInfoKHR& info, std::uint64_t frame, const char* eye) {
  Swapchain* swapchain = lookup<Swapchain>(info.subImage.swapchain);
  if (swapchain == nullptr || swapchain->lastReleased < 0 || (swapchain->aspect & VK_IMAGE_ASPECT_DEPTH_BIT) == 0) return;
  const VkFormat format = swapchain->format;
  const XrRect2Di rect = info.subImage.imageRect;
  vt::Image16 out(rect.extent.width, rect.extent.height, 1);
  // Copies of the depth aspect are tightly packed: 4 bytes for D32_SFLOAT and D24 (depth in the
  // low 24 bits), 2 for D16.
  const std::size_t pixelBytes = format == VK_FORMAT_D16_UNORM ? 2 : 4;
  const std::uint8_t* data =
      copyReleased(*swapchain, info.subImage, VK_IMAGE_ASPECT_DEPTH_BIT, out.pixels.size() * pixelBytes);
  for (std::size_t i = 0; i < out.pixels.size(); ++i) {
    float depth = 0.0f;
    if (format == VK_FORMAT_D16_UNORM) {
      std::uint16_t v = 0;
      std::memcpy(&v, data + i * 2, 2);
      depth = float(v) / 65535.0f;
    } else if (format == VK_FORMAT_D32_SFLOAT) {
      std::memcpy(&depth, data + i * 4, 4);
    } else {
      std::uint32_t v = 0;
      std::memcpy(&v, data + i * 4, 4);
      depth = float(v & 0xFFFFFFu) / 16777215.0f;
    }
    out.pixels[i] = std::uint16_t(std::lround(std::clamp(depth, 0.0f, 1.0f) * 65535.0f));
  }
  vt::savePng16(m_dir / fileName(frame, eye, "_depth"), out);
}

}  // namespace xrsim
