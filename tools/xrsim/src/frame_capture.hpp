#pragma once
// Reads submitted eye images back from the application's device and saves them as PNG.
#include <filesystem>
#include <string>

#include "objects.hpp"

namespace xrsim {

class FrameCapture {
 public:
  FrameCapture(Session& session, std::filesystem::path outputDir);
  ~FrameCapture();
  FrameCapture(const FrameCapture&) = delete;
  FrameCapture& operator=(const FrameCapture&) = delete;

  /// Copies the released image of one projection view into a PNG named
  /// frame_<frame>_<eye>.png (eye "left"/"right"). Called inside xrEndFrame.
  void save(const XrCompositionLayerProjectionView& view, std::uint64_t frame, const char* eye);
  /// Copies the released depth image of an XrCompositionLayerDepthInfoKHR into a 16-bit grey PNG
  /// frame_<frame>_<eye>_depth.png: window depth (0 near .. 1 far) scaled to 0..65535.
  void saveDepth(const XrCompositionLayerDepthInfoKHR& info, std::uint64_t frame, const char* eye);

 private:
  void ensureBuffer(VkDeviceSize size);
  /// Copies one layer's rect of the swapchain's last released image (in its resting layout,
  /// whose aspect is `aspect`) into m_buffer and waits; returns the mapped bytes.
  const std::uint8_t* copyReleased(const Swapchain& swapchain, const XrSwapchainSubImage& sub,
                                   VkImageAspectFlags aspect, VkDeviceSize bytes);
  void release() noexcept;

  Session& m_session;
  std::filesystem::path m_dir;
  VkBuffer m_buffer = VK_NULL_HANDLE;
  VkDeviceMemory m_memory = VK_NULL_HANDLE;
  VkDeviceSize m_size = 0;
  void* m_mapped = nullptr;
};

}  // namespace xrsim
