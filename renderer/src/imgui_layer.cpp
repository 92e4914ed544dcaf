#include "vt/renderer/imgui_layer.hpp"

#include <cmath>

#include <imgui.h>
#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_vulkan.h>

#include "gpu.hpp"
#include "imgui_images.hpp"
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

}  // namespace

ImGuiLayer::ImGuiLayer(Renderer& renderer, WindowTarget& window) : m_renderer(renderer) {
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
  ImGui_ImplGlfw_InitForVulkan(window.window(), true);
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
  ImGui_ImplVulkan_Init(&info, renderer.renderPassFor(window));
  submitOnce(dev, [](VkCommandBuffer cmd) { ImGui_ImplVulkan_CreateFontsTexture(cmd); });
  ImGui_ImplVulkan_DestroyFontUploadObjects();
  m_images = std::make_unique<ImGuiImages>(renderer, renderer.renderPassFor(window));
  renderer.setPassHook([images = m_images.get()](VkCommandBuffer cmd) {
    images->beginRecording(cmd);
    ImDrawData* data = ImGui::GetDrawData();
    if (data && data->Valid) ImGui_ImplVulkan_RenderDrawData(data, cmd);
  });
}

ImGuiLayer::~ImGuiLayer() {
  m_renderer.waitIdle();
  m_renderer.setPassHook({});
  m_images.reset();
  ImGui_ImplVulkan_Shutdown();
  ImGui_ImplGlfw_Shutdown();
  ImGui::DestroyContext();
  vkDestroyDescriptorPool(m_renderer.device().device(), m_pool, nullptr);
}

void ImGuiLayer::setSettingsFile(std::string path) {
  m_settingsFile = std::move(path);
  ImGui::GetIO().IniFilename = m_settingsFile.empty() ? nullptr : m_settingsFile.c_str();
}

void ImGuiLayer::beginFrame() {
  ImGui_ImplVulkan_NewFrame();
  ImGui_ImplGlfw_NewFrame();
  ImGui::NewFrame();
}

void ImGuiLayer::endFrame() { ImGui::Render(); }

void ImGuiLayer::setImage(std::uint32_t slot, const Image8& rgba) { m_images->set(slot, rgba); }

void ImGuiLayer::image(std::uint32_t slot, float width_px, float height_px) { m_images->draw(slot, width_px, height_px); }

}  // namespace vt::renderer
