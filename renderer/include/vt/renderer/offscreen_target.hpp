#pragma once
// Offscreen render target: colour images the renderer owns, read back to CPU images / PNG.
#include <memory>

#include "vt/renderer/device.hpp"
#include "vt/renderer/render_target.hpp"
#include "vt/scene/image.hpp"

namespace vt::renderer {

/// Two RGBA8 sRGB image arrays (one per frame in flight); frames are copied to the CPU only when
/// read back. Main thread only.
class OffscreenTarget final : public RenderTarget {
 public:
  /// layers = number of views (1 mono, 2 stereo).
  OffscreenTarget(std::shared_ptr<Device> device, std::uint32_t width, std::uint32_t height,
                  std::uint32_t layers = 1);
  ~OffscreenTarget() override;

  /// The last rendered frame's layer as RGBA8 (sRGB-encoded); waits for the GPU to finish it.
  /// Throws vt::Error when nothing was rendered yet.
  Image8 readback(std::uint32_t layer = 0);

  VkFormat colorFormat() const override { return VK_FORMAT_R8G8B8A8_SRGB; }
  VkExtent2D extent() const override { return m_extent; }
  std::uint32_t layers() const override { return m_layers; }
  std::uint32_t imageCount() const override { return kImages; }
  VkImageView imageView(std::uint32_t i) const override;
  VkImage image(std::uint32_t i) const override;
  VkImageLayout finalLayout() const override { return VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL; }
  std::uint64_t generation() const override { return 1; }
  bool acquire(std::uint32_t frameSlot, AcquiredImage& out) override;
  void submitted(const AcquiredImage& image, VkFence fence) override;

 private:
  static constexpr std::uint32_t kImages = 2;
  struct Slot;
  std::shared_ptr<Device> m_device;
  VkExtent2D m_extent{};
  std::uint32_t m_layers = 1;
  std::unique_ptr<Slot[]> m_slots;
  std::uint32_t m_next = 0;
  int m_last = -1;
};

}  // namespace vt::renderer
