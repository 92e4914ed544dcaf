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
//
// Optionally the owner also gives depth images (an OpenXR depth swapchain for
// XR_KHR_composition_layer_depth, usage DEPTH_STENCIL_ATTACHMENT, same extent and layers): the
// renderer then draws depth into them instead of its own depth image, stores it (depth 0 at
// near_m, 1 at far_m, cleared to 1) and leaves them in DEPTH_STENCIL_ATTACHMENT_OPTIMAL, as
// OpenXR requires at release. Their swapchain is acquired separately:
//   target.setCurrentDepthImage(depthIndex) before render().
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
  std::vector<VkImage> depthImages;   // optional: all images of a depth swapchain; empty = renderer's own depth
  VkFormat depthFormat = VK_FORMAT_UNDEFINED;  // their format (supportsExternalDepth must accept it)
};

/// Whether the renderer can draw into external depth images of this format on this device
/// (D32_SFLOAT, D24_UNORM_S8_UINT or D16_UNORM with optimal-tiling attachment support). Any thread.
bool supportsExternalDepth(const Device& device, VkFormat format);

/// Wraps external images (creates only image views; never destroys the images). Main thread only.
class ExternalTarget final : public RenderTarget {
 public:
  /// Throws vt::Error for an empty image list, zero extent, layers outside 1..2, a null image or
  /// a depth format that supportsExternalDepth rejects (when depth images are given).
  ExternalTarget(std::shared_ptr<Device> device, const ExternalImages& images);
  ~ExternalTarget() override;

  /// The image the next render() draws into (the index xrAcquireSwapchainImage returned).
  void setCurrentImage(std::uint32_t index);
  std::uint32_t currentImage() const { return m_current; }
  /// The depth image the next render() draws into (the depth swapchain's acquired index).
  void setCurrentDepthImage(std::uint32_t index);
  std::uint32_t currentDepthImage() const { return m_currentDepth; }

  VkFormat colorFormat() const override { return m_desc.format; }
  VkExtent2D extent() const override { return m_desc.extent; }
  std::uint32_t layers() const override { return m_desc.layers; }
  std::uint32_t imageCount() const override { return std::uint32_t(m_desc.images.size()); }
  VkImageView imageView(std::uint32_t i) const override { return m_views[i]; }
  VkImage image(std::uint32_t i) const override { return m_desc.images[i]; }
  VkImageLayout finalLayout() const override { return m_desc.finalLayout; }
  std::uint32_t depthImageCount() const override { return std::uint32_t(m_desc.depthImages.size()); }
  VkFormat depthFormat() const override { return m_desc.depthFormat; }
  VkImageView depthImageView(std::uint32_t i) const override { return m_depthViews[i]; }
  VkImage depthImage(std::uint32_t i) const override { return m_desc.depthImages[i]; }
  std::uint64_t generation() const override { return 1; }
  bool acquire(std::uint32_t frameSlot, AcquiredImage& out) override;
  void submitted(const AcquiredImage&, VkFence) override {}

 private:
  std::shared_ptr<Device> m_device;
  ExternalImages m_desc;
  std::vector<VkImageView> m_views;
  std::vector<VkImageView> m_depthViews;
  std::uint32_t m_current = 0;
  std::uint32_t m_currentDepth = 0;
};

}  // namespace vt::renderer
