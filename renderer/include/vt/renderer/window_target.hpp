#pragma once
// Render target for a desktop window: a GLFW window with a Vulkan swapchain (vsync or not),
// recreated on resize / VK_ERROR_OUT_OF_DATE_KHR, skipped while minimised. A software device on
// an X server without DRI3 presents through MIT-SHM instead (the host present: rendered images
// copied to host memory and put into the window by the target; docs/renderer.md, "Presenting").
#include <array>
#include <atomic>
#include <cstdint>
#include <functional>
#include <memory>
#include <mutex>
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
  /// The host present where it applies (above); false, or VT_PRESENT=swapchain in the
  /// environment, keeps the swapchain everywhere.
  bool hostPresent = true;
};

/// One input event of a window, stamped (SteadyClock) when GLFW delivered it.
struct WindowEvent {
  enum class Kind : std::uint8_t { Cursor, Button, Scroll, Key, Char };
  Kind kind = Kind::Cursor;
  std::int64_t t_ns = 0;
  double x = 0.0, y = 0.0;  // Cursor: window coordinates; Scroll: wheel offsets
  int code = 0;             // Button: GLFW_MOUSE_BUTTON_*; Key: GLFW_KEY_*; Char: Unicode code point
  int action = 0;           // Button, Key: GLFW_PRESS, GLFW_RELEASE or GLFW_REPEAT
  int mods = 0;             // GLFW_MOD_* bits
};

/// A window and its swapchain. The window is made and its events are processed on GLFW's main
/// thread (the thread that constructs it); the swapchain (acquire, submit, capture) and
/// takeUiEvents() may be driven from one other thread, a render thread, so that input is read
/// while frames are drawn.
class WindowTarget final : public RenderTarget {
 public:
  /// Throws vt::Error when no window or surface can be made, or the queue cannot present.
  WindowTarget(std::shared_ptr<Device> device, const WindowOptions& options = {});
  ~WindowTarget() override;

  /// The GLFW window (input callbacks, ImGui's GLFW backend).
  GLFWwindow* window() const { return m_window; }
  /// Any thread.
  bool shouldClose() const;
  /// Processes window events (main thread): each goes to the listener, then into the UI queue.
  void pollEvents();
  /// The same, waiting at most `timeout_s` for one (main thread).
  void waitEvents(double timeout_s);
  /// Called on the main thread for every event as pollEvents() processes it (input handling).
  void setEventListener(std::function<void(const WindowEvent&)> listener);
  /// Events processed since the last call, oldest first (the UI's input). Any one thread.
  std::vector<WindowEvent> takeUiEvents();
  /// The window's size in screen coordinates (the UI's display size). Any thread.
  std::array<int, 2> windowSize() const { return {m_windowWidth.load(), m_windowHeight.load()}; }
  /// Frame pacing: the next frame is presented once its rendering has finished and not before
  /// `t_ns` (SteadyClock), so every frame reaches the screen a planned time after the input it
  /// shows; 0 = present at once. Render thread.
  void presentAt(std::int64_t t_ns) { m_presentAt_ns = t_ns; }
  /// When the last frame's rendering finished (known only for paced frames; else 0) and when it
  /// reached the window system: vkQueuePresentKHR returned, or with the host present the X server
  /// has copied it. Render thread.
  std::int64_t lastRenderDone_ns() const { return m_renderDone_ns; }
  std::int64_t lastPresented_ns() const { return m_presented_ns; }
  /// Makes the next rendered frame also copy its image (before presenting it) for takeCapture().
  void requestCapture();
  /// The captured frame as RGBA8 (screenshots, tests); waits for the GPU. Throws vt::Error when no
  /// capture was requested and rendered, or the surface's images cannot be copied.
  Image8 takeCapture();
  /// Times the swapchain (or the host present's images) was (re)created.
  std::uint64_t swapchainCount() const { return m_generation; }
  /// True when frames go through the host present rather than a swapchain.
  bool hostPresent() const { return m_host != nullptr; }

  VkFormat colorFormat() const override { return m_format; }
  VkExtent2D extent() const override { return m_extent; }
  std::uint32_t layers() const override { return 1; }
  std::uint32_t imageCount() const override { return std::uint32_t(m_images.size()); }
  VkImageView imageView(std::uint32_t i) const override { return m_views[i]; }
  VkImage image(std::uint32_t i) const override { return m_images[i]; }
  VkImageLayout finalLayout() const override;
  std::uint64_t generation() const override { return m_generation; }
  bool acquire(std::uint32_t frameSlot, AcquiredImage& out) override;
  void recordAfterPass(VkCommandBuffer cmd, std::uint32_t imageIndex) override;
  void submitted(const AcquiredImage& image, VkFence fence) override;

 private:
  struct Capture;
  struct HostPresent;
  void openSwapchainSurface();
  void recreateSwapchain();
  void recreateHostImages();
  void destroySwapchainViews();
  void destroy() noexcept;
  void installCallbacks();
  void event(const WindowEvent& e);

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
  std::atomic<bool> m_needsRecreate{false};
  std::int64_t m_presentAt_ns = 0, m_renderDone_ns = 0, m_presented_ns = 0;
  // Written by GLFW's callbacks on the main thread, read by the render thread.
  std::atomic<int> m_framebufferWidth{0}, m_framebufferHeight{0}, m_windowWidth{0}, m_windowHeight{0};
  std::function<void(const WindowEvent&)> m_listener;
  std::mutex m_uiMutex;
  std::vector<WindowEvent> m_uiEvents;
  bool m_transferSrc = false;
  std::unique_ptr<Capture> m_capture;
  std::unique_ptr<HostPresent> m_host;
};

}  // namespace vt::renderer
