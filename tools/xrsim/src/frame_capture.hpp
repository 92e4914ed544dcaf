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

 private:
  void ensureBuffer(VkDeviceSize size);
  void release() noexcept;

  Session& m_session;
  std::filesystem::path m_dir;
  VkBuffer m_buffer = VK_NULL_HANDLE;
  VkDeviceMemory m_memory = VK_NULL_HANDLE;
  VkDeviceSize m_size = 0;
};

}  // namespace xrsim
