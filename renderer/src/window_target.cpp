#include "vt/renderer/window_target.hpp"

#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <string_view>
#include <utility>

#define GLFW_INCLUDE_VULKAN
#include <GLFW/glfw3.h>

#include "gpu.hpp"
#include "vt/core/clock.hpp"
#include "vt/core/error.hpp"
#include "vt/core/log.hpp"
#include "vt/renderer/renderer.hpp"
#include "vt/renderer/vk_check.hpp"
#include "x11_shm_present.hpp"

// GLFW's native accessor, declared here rather than through glfw3native.h (which needs Xrandr's headers).
extern "C" unsigned long glfwGetX11Window(GLFWwindow* window);

namespace vt::renderer {
namespace {

// GLFW is process-global: initialised while any user needs it, terminated after the last.
int g_glfwUsers = 0;

void acquireGlfw() {
  if (g_glfwUsers == 0) {
    glfwSetErrorCallback([](int code, const char* text) { log::warn("glfw error ", code, ": ", text); });
    if (!glfwInit()) fail("window: GLFW could not initialise (no display? set DISPLAY or use xvfb-run)");
    if (!glfwVulkanSupported()) {
      glfwTerminate();
      fail("window: GLFW found no Vulkan loader/ICD with surface support");
    }
  }
  ++g_glfwUsers;
}

void releaseGlfw() {
  if (--g_glfwUsers == 0) glfwTerminate();
}

}  // namespace

/// A pending or finished copy of one frame's image into host memory.
struct WindowTarget::Capture {
  GpuBuffer buffer;
  bool requested = false;
  bool recorded = false;
  VkFence fence = VK_NULL_HANDLE;
  std::uint32_t hostImage = 0;  // host present: the frame slot's readback buffer (valid until that slot draws again)
};

/// The host present: images the renderer draws into, each copied after its pass into a
/// host-visible buffer that the presenter puts into the window.
struct WindowTarget::HostPresent {
  std::unique_ptr<X11ShmPresenter> presenter;
  std::vector<GpuImage> images;
  std::vector<GpuBuffer> readback;
};

namespace {

// Software devices on X servers without DRI3 (Mesa's present there writes each frame into the X
// socket); VT_PRESENT=swapchain keeps the swapchain (tests of that path, troubleshooting).
bool wantsHostPresent(const Device& device, const WindowOptions& options) {
  const char* choice = std::getenv("VT_PRESENT");
  if (choice && std::string_view(choice) == "swapchain") return false;
  if (choice && *choice && std::string_view(choice) != "auto")
    log::warn("window: VT_PRESENT=", choice, " is not 'swapchain' or 'auto'; using auto");
  return options.hostPresent && device.isSoftware();
}

// Records a copy of a whole one-layer colour image, found in `layout`, into `buffer` (tight
// rows); the image is left in TRANSFER_SRC_OPTIMAL.
void recordCopyToBuffer(VkCommandBuffer cmd, VkImage image, VkImageLayout layout, VkExtent2D extent, VkBuffer buffer) {
  transitionImage(cmd, image, VK_IMAGE_ASPECT_COLOR_BIT, layout, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, 0, 1, 1);
  VkBufferImageCopy copy{};
  copy.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
  copy.imageExtent = {extent.width, extent.height, 1};
  vkCmdCopyImageToBuffer(cmd, image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, buffer, 1, &copy);
}

}  // namespace

void addWindowExtensions(DeviceOptions& options) {
  acquireGlfw();
  std::uint32_t count = 0;
  const char** names = glfwGetRequiredInstanceExtensions(&count);
  for (std::uint32_t i = 0; i < count; ++i) options.instanceExtensions.emplace_back(names[i]);
  releaseGlfw();
  options.deviceExtensions.emplace_back(VK_KHR_SWAPCHAIN_EXTENSION_NAME);
}

WindowTarget::WindowTarget(std::shared_ptr<Device> device, const WindowOptions& options)
    : m_device(std::move(device)), m_options(options) {
  acquireGlfw();
  glfwWindowHint(GLFW_CLIENT_API, GLFW_NO_API);
  glfwWindowHint(GLFW_RESIZABLE, options.resizable ? GLFW_TRUE : GLFW_FALSE);
  m_window = glfwCreateWindow(options.width, options.height, options.title.c_str(), nullptr, nullptr);
  if (!m_window) {
    releaseGlfw();
    fail("window: cannot create a ", options.width, "x", options.height, " window");
  }
  installCallbacks();
  try {
    if (wantsHostPresent(*m_device, options)) {
      if (auto presenter = X11ShmPresenter::open(glfwGetX11Window(m_window))) {
        m_host = std::make_unique<HostPresent>();
        m_host->presenter = std::move(presenter);
        m_format = VK_FORMAT_B8G8R8A8_SRGB;  // the X visual's B G R X bytes, sRGB-encoded as the swapchain's
        m_transferSrc = true;
        recreateHostImages();
        log::debug("window: host present (MIT-SHM)");
        return;
      }
    }
    openSwapchainSurface();
  } catch (...) {
    destroy();
    throw;
  }
}

void WindowTarget::openSwapchainSurface() {
  VT_VK(glfwCreateWindowSurface(m_device->instance(), m_window, nullptr, &m_surface));
  VkBool32 canPresent = VK_FALSE;
  VT_VK(vkGetPhysicalDeviceSurfaceSupportKHR(m_device->physicalDevice(), m_device->queueFamily(), m_surface, &canPresent));
  if (!canPresent) fail("window: the renderer's queue family cannot present to this window");
  std::uint32_t count = 0;
  VT_VK(vkGetPhysicalDeviceSurfaceFormatsKHR(m_device->physicalDevice(), m_surface, &count, nullptr));
  std::vector<VkSurfaceFormatKHR> formats(count);
  VT_VK(vkGetPhysicalDeviceSurfaceFormatsKHR(m_device->physicalDevice(), m_surface, &count, formats.data()));
  if (formats.empty()) fail("window: the surface offers no formats");
  // An sRGB format keeps the passes' output encoding identical to the offscreen target.
  auto srgb = std::find_if(formats.begin(), formats.end(), [](const VkSurfaceFormatKHR& f) {
    return (f.format == VK_FORMAT_B8G8R8A8_SRGB || f.format == VK_FORMAT_R8G8B8A8_SRGB) &&
           f.colorSpace == VK_COLOR_SPACE_SRGB_NONLINEAR_KHR;
  });
  if (srgb == formats.end()) log::warn("window: no sRGB surface format; colours will look dark");
  const VkSurfaceFormatKHR chosen = srgb != formats.end() ? *srgb : formats[0];
  m_format = chosen.format;
  m_colorSpace = chosen.colorSpace;
  VT_VK(vkGetPhysicalDeviceSurfacePresentModesKHR(m_device->physicalDevice(), m_surface, &count, nullptr));
  std::vector<VkPresentModeKHR> modes(count);
  VT_VK(vkGetPhysicalDeviceSurfacePresentModesKHR(m_device->physicalDevice(), m_surface, &count, modes.data()));
  m_presentMode = VK_PRESENT_MODE_FIFO_KHR;  // always available: vsync
  if (!m_options.vsync) {
    for (VkPresentModeKHR preferred : {VK_PRESENT_MODE_MAILBOX_KHR, VK_PRESENT_MODE_IMMEDIATE_KHR}) {
      if (std::find(modes.begin(), modes.end(), preferred) != modes.end()) {
        m_presentMode = preferred;
        break;
      }
    }
  }
  VkSemaphoreCreateInfo semaphoreInfo{VK_STRUCTURE_TYPE_SEMAPHORE_CREATE_INFO};
  for (VkSemaphore& s : m_imageAvailable) VT_VK(vkCreateSemaphore(m_device->device(), &semaphoreInfo, nullptr, &s));
  recreateSwapchain();
}

void WindowTarget::recreateHostImages() {
  VT_VK(vkDeviceWaitIdle(m_device->device()));  // rare (resize): the old images may still be in flight
  m_images.clear();
  m_views.clear();
  m_host->images.clear();
  m_host->readback.clear();
  m_extent = {std::uint32_t(std::max(0, m_framebufferWidth.load())), std::uint32_t(std::max(0, m_framebufferHeight.load()))};
  m_needsRecreate = false;
  if (m_extent.width == 0 || m_extent.height == 0) return;  // minimised: acquire() skips frames
  // One image per renderer frame slot: the renderer waits for a slot's fence before reusing it.
  for (int i = 0; i < 2; ++i) {
    ImageSpec spec;
    spec.format = m_format;
    spec.extent = m_extent;
    spec.usage = VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
    m_host->images.emplace_back(*m_device, spec, true);
    m_host->readback.emplace_back(*m_device, VkDeviceSize(m_extent.width) * m_extent.height * 4, VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                                  VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT);
    m_images.push_back(m_host->images.back().image);
    m_views.push_back(m_host->images.back().view);
  }
  ++m_generation;
  log::debug("window: host present images ", m_extent.width, "x", m_extent.height);
}

VkImageLayout WindowTarget::finalLayout() const {
  return m_host ? VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL : VK_IMAGE_LAYOUT_PRESENT_SRC_KHR;
}

WindowTarget::~WindowTarget() { destroy(); }

void WindowTarget::destroy() noexcept {
  VkDevice device = m_device->device();
  if (device) vkDeviceWaitIdle(device);
  if (m_host) {
    m_views.clear();  // the host images own their views
    m_host.reset();
  }
  destroySwapchainViews();
  for (VkSemaphore& s : m_imageAvailable) {
    if (s) vkDestroySemaphore(device, s, nullptr);
    s = VK_NULL_HANDLE;
  }
  m_capture.reset();
  if (m_swapchain) vkDestroySwapchainKHR(device, m_swapchain, nullptr);
  m_swapchain = VK_NULL_HANDLE;
  if (m_surface) vkDestroySurfaceKHR(m_device->instance(), m_surface, nullptr);
  m_surface = VK_NULL_HANDLE;
  if (m_window) {
    glfwDestroyWindow(m_window);
    m_window = nullptr;
    releaseGlfw();
  }
}

void WindowTarget::destroySwapchainViews() {
  for (VkImageView v : m_views) vkDestroyImageView(m_device->device(), v, nullptr);
  for (VkSemaphore s : m_renderDone) vkDestroySemaphore(m_device->device(), s, nullptr);
  m_views.clear();
  m_renderDone.clear();
}

void WindowTarget::recreateSwapchain() {
  VkDevice device = m_device->device();
  VT_VK(vkDeviceWaitIdle(device));  // rare (resize): the old images may still be in flight
  VkSurfaceCapabilitiesKHR caps;
  VT_VK(vkGetPhysicalDeviceSurfaceCapabilitiesKHR(m_device->physicalDevice(), m_surface, &caps));
  if (caps.currentExtent.width != std::numeric_limits<std::uint32_t>::max()) {
    m_extent = caps.currentExtent;
  } else {
    const auto w = std::uint32_t(m_framebufferWidth.load()), h = std::uint32_t(m_framebufferHeight.load());
    m_extent = {std::clamp(w, caps.minImageExtent.width, caps.maxImageExtent.width),
                std::clamp(h, caps.minImageExtent.height, caps.maxImageExtent.height)};
  }
  if (m_extent.width == 0 || m_extent.height == 0) return;  // minimised: acquire() skips frames
  std::uint32_t imageCount = std::max(caps.minImageCount + 1, 2u);
  if (caps.maxImageCount > 0) imageCount = std::min(imageCount, caps.maxImageCount);
  m_transferSrc = (caps.supportedUsageFlags & VK_IMAGE_USAGE_TRANSFER_SRC_BIT) != 0;
  VkSwapchainCreateInfoKHR info{VK_STRUCTURE_TYPE_SWAPCHAIN_CREATE_INFO_KHR};
  info.surface = m_surface;
  info.minImageCount = imageCount;
  info.imageFormat = m_format;
  info.imageColorSpace = m_colorSpace;
  info.imageExtent = m_extent;
  info.imageArrayLayers = 1;
  info.imageUsage = VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | (m_transferSrc ? VK_IMAGE_USAGE_TRANSFER_SRC_BIT : 0);
  info.imageSharingMode = VK_SHARING_MODE_EXCLUSIVE;
  info.preTransform = caps.currentTransform;
  info.compositeAlpha = (caps.supportedCompositeAlpha & VK_COMPOSITE_ALPHA_OPAQUE_BIT_KHR)
                            ? VK_COMPOSITE_ALPHA_OPAQUE_BIT_KHR
                            : VkCompositeAlphaFlagBitsKHR(caps.supportedCompositeAlpha & -caps.supportedCompositeAlpha);
  info.presentMode = m_presentMode;
  info.clipped = VK_TRUE;
  info.oldSwapchain = m_swapchain;
  VkSwapchainKHR created = VK_NULL_HANDLE;
  VT_VK(vkCreateSwapchainKHR(device, &info, nullptr, &created));
  destroySwapchainViews();
  if (m_swapchain) vkDestroySwapchainKHR(device, m_swapchain, nullptr);
  m_swapchain = created;
  std::uint32_t count = 0;
  VT_VK(vkGetSwapchainImagesKHR(device, m_swapchain, &count, nullptr));
  m_images.resize(count);
  VT_VK(vkGetSwapchainImagesKHR(device, m_swapchain, &count, m_images.data()));
  VkSemaphoreCreateInfo semaphoreInfo{VK_STRUCTURE_TYPE_SEMAPHORE_CREATE_INFO};
  for (VkImage image : m_images) {
    m_views.push_back(createView(device, image, m_format, VK_IMAGE_ASPECT_COLOR_BIT, 1, 1, true));
    VkSemaphore s = VK_NULL_HANDLE;
    VT_VK(vkCreateSemaphore(device, &semaphoreInfo, nullptr, &s));
    m_renderDone.push_back(s);
  }
  m_needsRecreate = false;
  ++m_generation;
  log::debug("window: swapchain ", m_extent.width, "x", m_extent.height, ", ", count, " images");
}

bool WindowTarget::shouldClose() const { return glfwWindowShouldClose(m_window); }

void WindowTarget::pollEvents() { glfwPollEvents(); }

void WindowTarget::waitEvents(double timeout_s) { glfwWaitEventsTimeout(timeout_s); }

void WindowTarget::setEventListener(std::function<void(const WindowEvent&)> listener) { m_listener = std::move(listener); }

std::vector<WindowEvent> WindowTarget::takeUiEvents() {
  std::vector<WindowEvent> events;
  const std::lock_guard lock(m_uiMutex);
  events.swap(m_uiEvents);
  return events;
}

void WindowTarget::event(const WindowEvent& e) {
  if (m_listener) m_listener(e);
  const std::lock_guard lock(m_uiMutex);
  // Without a UI draining them (tests, a window with no HUD) the oldest go.
  if (m_uiEvents.size() >= 4096) m_uiEvents.erase(m_uiEvents.begin(), m_uiEvents.begin() + 2048);
  m_uiEvents.push_back(e);
}

// GLFW calls these on the main thread from pollEvents(); each becomes a stamped WindowEvent.
void WindowTarget::installCallbacks() {
  int w = 0, h = 0;
  glfwGetFramebufferSize(m_window, &w, &h);
  m_framebufferWidth = w;
  m_framebufferHeight = h;
  glfwGetWindowSize(m_window, &w, &h);
  m_windowWidth = w;
  m_windowHeight = h;
  glfwSetWindowUserPointer(m_window, this);
  static constexpr auto self = [](GLFWwindow* window) { return static_cast<WindowTarget*>(glfwGetWindowUserPointer(window)); };
  static constexpr auto now = [] { return SteadyClock::instance().now_ns(); };
  glfwSetFramebufferSizeCallback(m_window, [](GLFWwindow* window, int width, int height) {
    self(window)->m_framebufferWidth = width;
    self(window)->m_framebufferHeight = height;
    self(window)->m_needsRecreate = true;
  });
  glfwSetWindowSizeCallback(m_window, [](GLFWwindow* window, int width, int height) {
    self(window)->m_windowWidth = width;
    self(window)->m_windowHeight = height;
  });
  glfwSetCursorPosCallback(m_window, [](GLFWwindow* window, double x, double y) {
    self(window)->event({.kind = WindowEvent::Kind::Cursor, .t_ns = now(), .x = x, .y = y});
  });
  glfwSetMouseButtonCallback(m_window, [](GLFWwindow* window, int button, int action, int mods) {
    self(window)->event({.kind = WindowEvent::Kind::Button, .t_ns = now(), .code = button, .action = action, .mods = mods});
  });
  glfwSetScrollCallback(m_window, [](GLFWwindow* window, double x, double y) {
    self(window)->event({.kind = WindowEvent::Kind::Scroll, .t_ns = now(), .x = x, .y = y});
  });
  glfwSetKeyCallback(m_window, [](GLFWwindow* window, int key, int, int action, int mods) {
    self(window)->event({.kind = WindowEvent::Kind::Key, .t_ns = now(), .code = key, .action = action, .mods = mods});
  });
  glfwSetCharCallback(m_window, [](GLFWwindow* window, unsigned codepoint) {
    self(window)->event({.kind = WindowEvent::Kind::Char, .t_ns = now(), .code = int(codepoint)});
  });
}

bool WindowTarget::acquire(std::uint32_t frameSlot, AcquiredImage& out) {
  if (m_framebufferWidth.load() == 0 || m_framebufferHeight.load() == 0) return false;  // minimised
  if (m_host) {
    if (m_needsRecreate || m_extent.width != std::uint32_t(m_framebufferWidth.load()) ||
        m_extent.height != std::uint32_t(m_framebufferHeight.load()))
      recreateHostImages();
    if (m_images.empty()) return false;
    out.index = frameSlot % std::uint32_t(m_images.size());
    out.waitSemaphore = out.signalSemaphore = VK_NULL_HANDLE;
    return true;
  }
  if (m_needsRecreate || !m_swapchain || m_extent.width == 0) recreateSwapchain();
  if (!m_swapchain || m_extent.width == 0) return false;
  const VkSemaphore available = m_imageAvailable[frameSlot % m_imageAvailable.size()];
  std::uint32_t index = 0;
  const VkResult result = vkAcquireNextImageKHR(m_device->device(), m_swapchain, std::numeric_limits<std::uint64_t>::max(),
                                                available, VK_NULL_HANDLE, &index);
  if (result == VK_ERROR_OUT_OF_DATE_KHR) {
    m_needsRecreate = true;  // nothing was signalled: skip this frame, recreate on the next
    return false;
  }
  VT_VK(result);
  if (result == VK_SUBOPTIMAL_KHR) m_needsRecreate = true;  // still usable this frame
  out.index = index;
  out.waitSemaphore = available;
  out.signalSemaphore = m_renderDone[index];
  return true;
}

void WindowTarget::submitted(const AcquiredImage& image, VkFence fence) {
  if (m_capture && m_capture->recorded) m_capture->fence = fence;
  const Clock& clock = SteadyClock::instance();
  m_renderDone_ns = 0;
  if (m_host) {
    // The pixels are read here: wait for them, copy them into the shared segment, then put them
    // at the planned moment.
    VT_VK(vkWaitForFences(m_device->device(), 1, &fence, VK_TRUE, std::numeric_limits<std::uint64_t>::max()));
    if (m_presentAt_ns > 0) m_renderDone_ns = clock.now_ns();
    const GpuBuffer& frame = m_host->readback[image.index];
    std::memcpy(m_host->presenter->pixels(m_extent.width, m_extent.height), frame.mapped, std::size_t(frame.size));
    if (m_presentAt_ns > 0) clock.sleepUntil(m_presentAt_ns);
    m_presentAt_ns = 0;
    m_host->presenter->put();
    m_presented_ns = clock.now_ns();
    return;
  }
  if (m_presentAt_ns > 0) {
    VT_VK(vkWaitForFences(m_device->device(), 1, &fence, VK_TRUE, std::numeric_limits<std::uint64_t>::max()));
    m_renderDone_ns = clock.now_ns();
    clock.sleepUntil(m_presentAt_ns);
    m_presentAt_ns = 0;
  }
  VkPresentInfoKHR present{VK_STRUCTURE_TYPE_PRESENT_INFO_KHR};
  present.waitSemaphoreCount = 1;
  present.pWaitSemaphores = &image.signalSemaphore;
  present.swapchainCount = 1;
  present.pSwapchains = &m_swapchain;
  present.pImageIndices = &image.index;
  const VkResult result = vkQueuePresentKHR(m_device->queue(), &present);
  m_presented_ns = clock.now_ns();
  if (result == VK_ERROR_OUT_OF_DATE_KHR || result == VK_SUBOPTIMAL_KHR) {
    m_needsRecreate = true;
  } else {
    VT_VK(result);
  }
}

void WindowTarget::requestCapture() {
  if (!m_transferSrc) fail("window: this surface's images cannot be copied (no TRANSFER_SRC usage)");
  if (!m_capture) m_capture = std::make_unique<Capture>();
  m_capture->requested = true;
  m_capture->recorded = false;
}

void WindowTarget::recordAfterPass(VkCommandBuffer cmd, std::uint32_t imageIndex) {
  if (m_host) {
    // Every frame goes to host memory; a capture reads the same buffer.
    recordCopyToBuffer(cmd, m_images[imageIndex], VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, m_extent,
                       m_host->readback[imageIndex].buffer);
    VkMemoryBarrier toHost{VK_STRUCTURE_TYPE_MEMORY_BARRIER};
    toHost.srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
    toHost.dstAccessMask = VK_ACCESS_HOST_READ_BIT;
    vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_HOST_BIT, 0, 1, &toHost, 0, nullptr, 0, nullptr);
    if (m_capture && m_capture->requested) {
      m_capture->requested = false;
      m_capture->recorded = true;
      m_capture->hostImage = imageIndex;
    }
    return;
  }
  if (!m_capture || !m_capture->requested) return;
  // Copied inside the frame's own submission, while the image is still ours (before present).
  const VkDeviceSize bytes = VkDeviceSize(m_extent.width) * m_extent.height * 4;
  if (m_capture->buffer.size != bytes) {
    m_capture->buffer = GpuBuffer(*m_device, bytes, VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                                  VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT);
  }
  const VkImage image = m_images[imageIndex];
  recordCopyToBuffer(cmd, image, VK_IMAGE_LAYOUT_PRESENT_SRC_KHR, m_extent, m_capture->buffer.buffer);
  transitionImage(cmd, image, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                  VK_IMAGE_LAYOUT_PRESENT_SRC_KHR, 0, 1, 1);
  m_capture->requested = false;
  m_capture->recorded = true;
}

Image8 WindowTarget::takeCapture() {
  if (!m_capture || !m_capture->recorded) fail("window: no captured frame (requestCapture, then render)");
  VT_VK(vkWaitForFences(m_device->device(), 1, &m_capture->fence, VK_TRUE, std::numeric_limits<std::uint64_t>::max()));
  Image8 out(int(m_extent.width), int(m_extent.height), 4);
  const GpuBuffer& source = m_host ? m_host->readback[m_capture->hostImage] : m_capture->buffer;
  std::memcpy(out.pixels.data(), source.mapped, out.pixels.size());
  if (m_format == VK_FORMAT_B8G8R8A8_SRGB || m_format == VK_FORMAT_B8G8R8A8_UNORM) {
    for (std::size_t i = 0; i < out.pixels.size(); i += 4) std::swap(out.pixels[i], out.pixels[i + 2]);
  }
  m_capture->recorded = false;
  return out;
}

}  // namespace vt::renderer
