#pragma once
// Where a frame goes. The passes only see this interface, so the offscreen target, a GLFW
// window swapchain and OpenXR swapchain images (created by the runtime, not owned by the
// renderer) are interchangeable. Images are 2D arrays with layers() layers: one per view
// (stereo renders both eyes in one pass with multiview). Vulkan types are fine here: this is the
// target-creation side of the API, not the scene/frame description.
#include <cstdint>

#include <vulkan/vulkan.h>

namespace vt::renderer {

/// What a target hands the renderer for one frame.
struct AcquiredImage {
  std::uint32_t index = 0;                   // which of imageCount() images to draw into
  VkSemaphore waitSemaphore = VK_NULL_HANDLE;  // signalled when the image may be written (window)
  VkSemaphore signalSemaphore = VK_NULL_HANDLE;  // the renderer signals it when drawing is done (present)
  std::uint32_t depthIndex = 0;              // which of depthImageCount() depth images (when the target has them)
};

/// A set of colour images (optionally with depth images) the renderer draws into. Main (render) thread only.
class RenderTarget {
 public:
  virtual ~RenderTarget() = default;
  /// Unique per target object for the process lifetime (keys the renderer's framebuffer cache).
  std::uint64_t targetId() const { return m_targetId; }

  virtual VkFormat colorFormat() const = 0;
  virtual VkExtent2D extent() const = 0;
  /// Array layers per image = number of views rendered with multiview (1 or 2).
  virtual std::uint32_t layers() const = 0;
  virtual std::uint32_t imageCount() const = 0;
  /// A 2D-array view of all layers of image i (owned by the target).
  virtual VkImageView imageView(std::uint32_t i) const = 0;
  virtual VkImage image(std::uint32_t i) const = 0;
  /// The layout the render pass leaves the image in (transfer src, present src, attachment).
  virtual VkImageLayout finalLayout() const = 0;
  /// Depth images the target owns (e.g. an OpenXR depth swapchain): the renderer draws depth into
  /// them, stores it and leaves them in DEPTH_STENCIL_ATTACHMENT_OPTIMAL. 0 = the renderer uses its
  /// own depth images, whose contents are discarded.
  virtual std::uint32_t depthImageCount() const { return 0; }
  /// The format of the target's depth images (UNDEFINED when it has none).
  virtual VkFormat depthFormat() const { return VK_FORMAT_UNDEFINED; }
  /// A 2D-array view of all layers of depth image i, and the image (only when depthImageCount() > 0).
  virtual VkImageView depthImageView(std::uint32_t /*i*/) const { return VK_NULL_HANDLE; }
  virtual VkImage depthImage(std::uint32_t /*i*/) const { return VK_NULL_HANDLE; }
  /// Changes whenever images are recreated (resize): the renderer rebuilds its framebuffers.
  virtual std::uint64_t generation() const = 0;

  /// Chooses the image for the next frame; false = skip this frame (e.g. minimised window).
  /// `frameSlot` is the renderer's double-buffer slot (0/1) for per-slot semaphores.
  virtual bool acquire(std::uint32_t frameSlot, AcquiredImage& out) = 0;
  /// Records commands after the render pass into the frame's command buffer (readback copies).
  virtual void recordAfterPass(VkCommandBuffer, std::uint32_t /*imageIndex*/) {}
  /// Called after the frame was submitted; `fence` signals when the GPU finished it.
  virtual void submitted(const AcquiredImage& image, VkFence fence) = 0;

 protected:
  RenderTarget();

 private:
  std::uint64_t m_targetId;
};

}  // namespace vt::renderer
