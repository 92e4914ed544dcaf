#include "vt/renderer/imgui_layer.hpp"

#include <algorithm>
#include <cmath>

#include <utility>

#include <GLFW/glfw3.h>
#include <imgui.h>
#include <backends/imgui_impl_vulkan.h>

#include "gpu.hpp"
#include "imgui_images.hpp"
#include "vt/core/clock.hpp"
#include "vt/core/error.hpp"
#include "vt/core/log.hpp"
#include "vt/renderer/vk_check.hpp"

namespace vt::renderer {
namespace {

// ImGui's colours are sRGB values, but it draws into the sRGB attachment that encodes once more:
// decode the style to linear so panels look as designed.
float srgbToLinear(float c) { return c <= 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f); }

// ImGui's backend calls this with every VkResult it gets; it runs inside ImGui, so log, not throw.
void checkImGuiVk(VkResult result) {
  if (result < 0) log::error("imgui vulkan backend: ", resultName(result));
}

// ImGui's key indices are GLFW key codes; these keys drive its widgets (text fields, navigation).
void mapKeys(ImGuiIO& io) {
  const std::pair<ImGuiKey, int> keys[] = {
      {ImGuiKey_Tab, GLFW_KEY_TAB},         {ImGuiKey_LeftArrow, GLFW_KEY_LEFT}, {ImGuiKey_RightArrow, GLFW_KEY_RIGHT},
      {ImGuiKey_UpArrow, GLFW_KEY_UP},      {ImGuiKey_DownArrow, GLFW_KEY_DOWN}, {ImGuiKey_PageUp, GLFW_KEY_PAGE_UP},
      {ImGuiKey_PageDown, GLFW_KEY_PAGE_DOWN}, {ImGuiKey_Home, GLFW_KEY_HOME}, {ImGuiKey_End, GLFW_KEY_END},
      {ImGuiKey_Insert, GLFW_KEY_INSERT},   {ImGuiKey_Delete, GLFW_KEY_DELETE}, {ImGuiKey_Backspace, GLFW_KEY_BACKSPACE},
      {ImGuiKey_Space, GLFW_KEY_SPACE},     {ImGuiKey_Enter, GLFW_KEY_ENTER},    {ImGuiKey_Escape, GLFW_KEY_ESCAPE},
      {ImGuiKey_KeyPadEnter, GLFW_KEY_KP_ENTER}, {ImGuiKey_A, GLFW_KEY_A},      {ImGuiKey_C, GLFW_KEY_C},
      {ImGuiKey_V, GLFW_KEY_V},             {ImGuiKey_X, GLFW_KEY_X},            {ImGuiKey_Y, GLFW_KEY_Y},
      {ImGuiKey_Z, GLFW_KEY_Z}};
  for (const auto& [key, glfw] : keys) io.KeyMap[key] = glfw;
}

}  // namespace

float textScaleForHeight(int height_px) noexcept {
  // 720 px is the scale the HUD was laid out at; below 900 px it stays as designed.
  return std::max(1.0f, std::floor(float(height_px) / 720.0f * 4.0f) / 4.0f);
}

ImGuiLayer::ImGuiLayer(Renderer& renderer, WindowTarget& window) : m_renderer(renderer), m_window(window) {
  if (ImGui::GetCurrentContext()) fail("imgui: a context already exists (one ImGuiLayer per process)");
  const Device& dev = renderer.device();
  const VkDescriptorPoolSize size{VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 16};
  VkDescriptorPoolCreateInfo poolInfo{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
  poolInfo.flags = VK_DESCRIPTOR_POOL_CREATE_FREE_DESCRIPTOR_SET_BIT;
  poolInfo.maxSets = 16;
  poolInfo.poolSizeCount = 1;
  poolInfo.pPoolSizes = &size;
  VT_VK(vkCreateDescriptorPool(dev.device(), &poolInfo, nullptr, &m_pool));

  ImGui::CreateContext();
  ImGui::GetIO().IniFilename = nullptr;  // no imgui.ini next to wherever the program runs (setSettingsFile)
  ImGui::StyleColorsDark();
  for (ImVec4& c : ImGui::GetStyle().Colors) c = {srgbToLinear(c.x), srgbToLinear(c.y), srgbToLinear(c.z), c.w};
  m_baseStyle = std::make_unique<ImGuiStyle>(ImGui::GetStyle());
  ImGuiIO& io = ImGui::GetIO();
  io.BackendPlatformName = "vtouching window events";
  mapKeys(io);
  buildFont(textScaleForHeight(window.windowSize()[1]));
  m_images = std::make_unique<ImGuiImages>(renderer, renderer.renderPassFor(window));
  renderer.setPassHook([images = m_images.get()](VkCommandBuffer cmd) {
    images->beginRecording(cmd);
    ImDrawData* data = ImGui::GetDrawData();
    if (data && data->Valid) ImGui_ImplVulkan_RenderDrawData(data, cmd);
  });
}

void ImGuiLayer::buildFont(float scale) {
  // ImGui's default font (ProggyClean, fixed width: numbers keep their columns) at the size
  // asked; 13 px is its design size.
  ImGuiIO& io = ImGui::GetIO();
  io.Fonts->Clear();
  ImFontConfig font;
  font.SizePixels = std::round(13.0f * scale);
  io.Fonts->AddFontDefault(&font);
  ImGuiStyle& style = ImGui::GetStyle();
  style = *m_baseStyle;
  style.ScaleAllSizes(scale);
  // Debian's ImGui 1.86 Vulkan backend cannot replace its font image in place: restart it (its
  // descriptor set is not freed by the backend: the pool is the backend's alone, reset it).
  const Device& dev = m_renderer.device();
  if (m_textScale != 0.0f) {
    ImGui_ImplVulkan_Shutdown();
    VT_VK(vkResetDescriptorPool(dev.device(), m_pool, 0));
  }
  ImGui_ImplVulkan_InitInfo info{};
  info.Instance = dev.instance();
  info.PhysicalDevice = dev.physicalDevice();
  info.Device = dev.device();
  info.QueueFamily = dev.queueFamily();
  info.Queue = dev.queue();
  info.DescriptorPool = m_pool;
  // ImGui rotates its own vertex buffers per draw; more than the frames in flight keeps them safe.
  info.MinImageCount = Renderer::kFramesInFlight;
  info.ImageCount = Renderer::kFramesInFlight + 1;
  info.MSAASamples = VK_SAMPLE_COUNT_1_BIT;
  info.CheckVkResultFn = &checkImGuiVk;
  ImGui_ImplVulkan_Init(&info, m_renderer.renderPassFor(m_window));
  submitOnce(dev, [](VkCommandBuffer cmd) { ImGui_ImplVulkan_CreateFontsTexture(cmd); });
  ImGui_ImplVulkan_DestroyFontUploadObjects();
  m_textScale = scale;
}

ImGuiLayer::~ImGuiLayer() {
  m_renderer.waitIdle();
  m_renderer.setPassHook({});
  m_images.reset();
  ImGui_ImplVulkan_Shutdown();
  ImGui::DestroyContext();
  vkDestroyDescriptorPool(m_renderer.device().device(), m_pool, nullptr);
}

void ImGuiLayer::setSettingsFile(std::string path) {
  m_settingsFile = std::move(path);
  ImGui::GetIO().IniFilename = m_settingsFile.empty() ? nullptr : m_settingsFile.c_str();
}

void ImGuiLayer::applyEvents() {
  ImGuiIO& io = ImGui::GetIO();
  // A button pressed and released since the last frame counts as held for this one, or the
  // click would be lost; its release comes with the next frame.
  for (int b = 0; b < kButtons; ++b) {
    if (m_releaseNextFrame[std::size_t(b)]) io.MouseDown[b] = false;
    m_releaseNextFrame[std::size_t(b)] = false;
  }
  std::array<bool, kButtons> pressed{};
  for (const WindowEvent& e : m_window.takeUiEvents()) {
    switch (e.kind) {
      case WindowEvent::Kind::Cursor:
        io.MousePos = {float(e.x), float(e.y)};
        break;
      case WindowEvent::Kind::Button:
        if (e.code < 0 || e.code >= kButtons) break;
        if (e.action == GLFW_PRESS) {
          io.MouseDown[e.code] = pressed[std::size_t(e.code)] = true;
        } else if (pressed[std::size_t(e.code)]) {
          m_releaseNextFrame[std::size_t(e.code)] = true;
        } else {
          io.MouseDown[e.code] = false;
        }
        break;
      case WindowEvent::Kind::Scroll:
        io.MouseWheelH += float(e.x);
        io.MouseWheel += float(e.y);
        break;
      case WindowEvent::Kind::Key:
        if (e.code >= 0 && e.code < int(IM_ARRAYSIZE(io.KeysDown))) io.KeysDown[e.code] = e.action != GLFW_RELEASE;
        io.KeyCtrl = (e.mods & GLFW_MOD_CONTROL) != 0;
        io.KeyShift = (e.mods & GLFW_MOD_SHIFT) != 0;
        io.KeyAlt = (e.mods & GLFW_MOD_ALT) != 0;
        io.KeySuper = (e.mods & GLFW_MOD_SUPER) != 0;
        break;
      case WindowEvent::Kind::Char:
        io.AddInputCharacter(unsigned(e.code));
        break;
    }
  }
}

void ImGuiLayer::beginFrame() {
  ImGuiIO& io = ImGui::GetIO();
  const auto [w, h] = m_window.windowSize();
  // Between frames: the font image may still be read by frames in flight, so wait for them.
  if (h > 0 && textScaleForHeight(h) != m_textScale) {
    m_renderer.waitIdle();
    buildFont(textScaleForHeight(h));
  }
  const VkExtent2D extent = m_window.extent();
  io.DisplaySize = {float(w), float(h)};
  if (w > 0 && h > 0) io.DisplayFramebufferScale = {float(extent.width) / float(w), float(extent.height) / float(h)};
  const std::int64_t now_ns = SteadyClock::instance().now_ns();
  io.DeltaTime = m_lastFrame_ns ? std::max(1e-4f, float(double(now_ns - m_lastFrame_ns) * 1e-9)) : 1.0f / 60.0f;
  m_lastFrame_ns = now_ns;
  applyEvents();
  ImGui_ImplVulkan_NewFrame();
  ImGui::NewFrame();
}

void ImGuiLayer::endFrame() {
  ImGui::Render();
  const ImGuiIO& io = ImGui::GetIO();
  m_wantsMouse.store(io.WantCaptureMouse, std::memory_order_relaxed);
  m_wantsKeyboard.store(io.WantCaptureKeyboard, std::memory_order_relaxed);
}

void ImGuiLayer::setImage(std::uint32_t slot, const Image8& rgba) { m_images->set(slot, rgba); }

void ImGuiLayer::image(std::uint32_t slot, float width_px, float height_px) { m_images->draw(slot, width_px, height_px); }

}  // namespace vt::renderer
