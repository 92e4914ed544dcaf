#pragma once
// Render target for a desktop window: a GLFW window with a Vulkan swapchain (vsync or not),
// recreated on resize / VK_ERROR_OUT_OF_DATE_KHR, skipped while minimised.
#include <array>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "vt/renderer/device.hpp"
#include "vt/renderer/render_target.hpp"
#include "vt/scene/image.hpp"

struct GLFWwindow;

namespace vt::renderer {

/// Adds GLFW's surface instance extensions and VK_KHR_swapchain to device options (call before
/// Device::create). Throws vt::Error when GLFW cannot start (no display) or lacks Vulkan.
void addWindowExtensions(DeviceOptions& options);

struct WindowOptions {
  int width = 1280;
  int height = 720;
  std::string title = "V-Touching";
  bool vsync = true;       // FIFO; otherwise MAILBOX or IMMEDIATE when offered
  bool resizable = true;
};

/// A window and its swapchain. Main thread only (GLFW's rule).
class WindowTarget final : public RenderTarget {
 public:
  /// Throws vt::Error when no window or surface can be made, or the queue cannot present.
  WindowTarget(std::shared_ptr<Device> device, const WindowOptions& options = {});
  ~WindowTarget() override;

  /// The GLFW window (input callbacks, ImGui's GLFW backend).
  GLFWwindow* window() const { return m_window; }
  bool shouldClose() const;
  /// Processes window events (call once per frame).
  void pollEvents();
  /// Makes the next rendered frame also copy its image (before presenting it) for takeCapture().
  void requestCapture();
  /// The captured frame as RGBA8 (screenshots, tests); waits for the GPU. Throws vt::Error when no
  /// capture was requested and rendered, or the surface's images cannot be copied.
  Image8 takeCapture();
  /// Times the swapchain was (re)created.
  std::uint64_t swapchainCount() const { return m_generation; }

  VkFormat colorFormat() const override { return m_format; }
  VkExtent2D extent() const override { return m_extent; }
  std::uint32_t layers() const override { return 1; }
  std::uint32_t imageCount() const override { return std::uint32_t(m_images.size()); }
  VkImageView imageView(std::uint32_t i) const override { return m_views[i]; }
  VkImage image(std::uint32_t i) const override { return m_images[i]; }
  VkImageLayout finalLayout() const override { return VK_IMAGE_LAYOUT_PRESENT_SRC_KHR; }
  std::uint64_t generation() const override { return m_generation; }
  bool acquire(std::uint32_t frameSlot, AcquiredImage& out) override;
  void recordAfterPass(VkCommandBuffer cmd, std::uint32_t imageIndex) override;
  void submitted(const AcquiredImage& image, VkFence fence) override;

 private:
  struct Capture;
  void recreateSwapchain();
  void destroySwapchainViews();
  void destroy() noexcept;

  std::shared_ptr<Device> m_device;
  WindowOptions m_options;
  GLFWwindow* m_window = nullptr;
  VkSurfaceKHR m_surface = VK_NULL_HANDLE;
  VkSwapchainKHR m_swapchain = VK_NULL_HANDLE;
  VkFormat m_format = VK_FORMAT_UNDEFINED;
  VkColorSpaceKHR m_colorSpace = VK_COLOR_SPACE_SRGB_NONLINEAR_KHR;
  VkPresentModeKHR m_presentMode = VK_PRESENT_MODE_FIFO_KHR;
  VkExtent2D m_extent{};
  std::vector<VkImage> m_images;
  std::vector<VkImageView> m_views;
  std::vector<VkSemaphore> m_renderDone;          // per swapchain image: drawing finished -> present
  std::array<VkSemaphore, 2> m_imageAvailable{};  // per renderer frame slot: acquire -> drawing
  std::uint64_t m_generation = 0;
  bool m_needsRecreate = false;
  bool m_transferSrc = false;
  std::unique_ptr<Capture> m_capture;
};

}  // namespace vt::renderer
