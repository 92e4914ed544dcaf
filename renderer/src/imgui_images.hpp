#pragma once
// RGBA8 images shown in Dear ImGui windows (internal to ImGuiLayer). The Debian ImGui 1.86
// Vulkan backend binds only its font texture, so an image is drawn by an ImDrawList callback
// with a small pipeline of its own, after which ImGui's render state is reset.
#include <array>
#include <cstdint>

#include <imgui.h>

#include "gpu.hpp"
#include "vt/renderer/renderer.hpp"
#include "vt/scene/image.hpp"

namespace vt::renderer {

class ImGuiImages {
 public:
  static constexpr std::uint32_t kSlots = 4;

  /// Builds the pipeline for `renderPass` (the window's). `renderer` must outlive this.
  ImGuiImages(Renderer& renderer, VkRenderPass renderPass);
  ~ImGuiImages();
  ImGuiImages(const ImGuiImages&) = delete;
  ImGuiImages& operator=(const ImGuiImages&) = delete;

  /// Uploads `rgba` (sRGB-encoded RGBA8) into `slot`; the GPU image is reused while the size
  /// stays the same, else rebuilt after the frames in flight finished.
  void set(std::uint32_t slot, const Image8& rgba);
  /// An ImGui item of the given size showing the slot (an empty frame before the first set).
  void draw(std::uint32_t slot, float width_px, float height_px);
  /// The pass hook tells which command buffer ImGui is being recorded into.
  void beginRecording(VkCommandBuffer cmd) noexcept { m_cmd = cmd; }

 private:
  struct Slot {
    ImGuiImages* owner = nullptr;
    GpuImage image;
    GpuBuffer staging;
    VkDescriptorSet set = VK_NULL_HANDLE;
    bool ready = false;
    ImVec2 min{}, max{};  // where this frame's draw() placed it (screen pixels)
  };
  static void onDraw(const ImDrawList* list, const ImDrawCmd* command);

  Renderer& m_renderer;
  VkDevice m_device = VK_NULL_HANDLE;
  VkSampler m_sampler = VK_NULL_HANDLE;
  VkDescriptorSetLayout m_setLayout = VK_NULL_HANDLE;
  VkDescriptorPool m_pool = VK_NULL_HANDLE;
  VkPipelineLayout m_layout = VK_NULL_HANDLE;
  VkPipeline m_pipeline = VK_NULL_HANDLE;
  VkCommandBuffer m_cmd = VK_NULL_HANDLE;
  std::array<Slot, kSlots> m_slots;
};

}  // namespace vt::renderer
