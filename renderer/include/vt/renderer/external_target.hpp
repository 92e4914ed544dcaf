#pragma once
// Render target over images someone else created and owns: OpenXR swapchain images
// (xrEnumerateSwapchainImages with XrSwapchainImageVulkan2KHR), on the device the runtime
// created through XR_KHR_vulkan_enable2 (see DeviceCreationHooks / Device::adopt).
//
// Per frame (render thread), for a swapchain created with usage COLOR_ATTACHMENT:
//   xrAcquireSwapchainImage -> index; xrWaitSwapchainImage;
//   target.setCurrentImage(index); renderer.render(target, frame);  // submitted on return
//   xrReleaseSwapchainImage.
// The image is left in finalLayout (COLOR_ATTACHMENT_OPTIMAL by default, as OpenXR requires at
// release). One swapchain with arraySize 2 = both eyes in one multiview pass (FrameDesc with two
// views); two swapchains with arraySize 1 = two targets, one render() each with one view.
#include <cstdint>
#include <memory>
#include <vector>

#include "vt/renderer/device.hpp"
#include "vt/renderer/render_target.hpp"

namespace vt::renderer {

/// What the owner of the images tells the target.
struct ExternalImages {
  std::vector<VkImage> images;        // all images of the swapchain, in its order
  VkFormat format = VK_FORMAT_R8G8B8A8_SRGB;  // the swapchain format (an _SRGB one keeps colours right)
  VkExtent2D extent{};
  std::uint32_t layers = 1;           // swapchain arraySize: 1, or 2 for multiview stereo
  VkImageLayout finalLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
};

/// Wraps external images (creates only image views; never destroys the images). Main thread only.
class ExternalTarget final : public RenderTarget {
 public:
  /// Throws vt::Error for an empty image list, zero extent or layers outside 1..2.
  ExternalTarget(std::shared_ptr<Device> device, const ExternalImages& images);
  ~ExternalTarget() override;

  /// The image the next render() draws into (the index xrAcquireSwapchainImage returned).
  void setCurrentImage(std::uint32_t index);
  std::uint32_t currentImage() const { return m_current; }

  VkFormat colorFormat() const override { return m_desc.format; }
  VkExtent2D extent() const override { return m_desc.extent; }
  std::uint32_t layers() const override { return m_desc.layers; }
  std::uint32_t imageCount() const override { return std::uint32_t(m_desc.images.size()); }
  VkImageView imageView(std::uint32_t i) const override { return m_views[i]; }
  VkImage image(std::uint32_t i) const override { return m_desc.images[i]; }
  VkImageLayout finalLayout() const override { return m_desc.finalLayout; }
  std::uint64_t generation() const override { return 1; }
  bool acquire(std::uint32_t frameSlot, AcquiredImage& out) override;
  void submitted(const AcquiredImage&, VkFence) override {}

 private:
  std::shared_ptr<Device> m_device;
  ExternalImages m_desc;
  std::vector<VkImageView> m_views;
  std::uint32_t m_current = 0;
};

}  // namespace vt::renderer
