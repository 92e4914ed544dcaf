#pragma once
// Dear ImGui on a window target: GLFW input and Vulkan drawing inside the renderer's own render
// pass (through Renderer::setPassHook), so UI panels cost no extra pass. Main thread only.
// The window's attachment is sRGB, so ImGui colours are linear: the layer converts its style;
// give custom widget colours in linear RGB too.
#include "vt/renderer/renderer.hpp"
#include "vt/renderer/window_target.hpp"

namespace vt::renderer {

/// Owns the ImGui context and its GLFW + Vulkan backends. One per process.
class ImGuiLayer {
 public:
  /// Creates the context, uploads the font and installs the pass hook on `renderer`.
  /// Both must outlive this object.
  ImGuiLayer(Renderer& renderer, WindowTarget& window);
  ~ImGuiLayer();
  ImGuiLayer(const ImGuiLayer&) = delete;
  ImGuiLayer& operator=(const ImGuiLayer&) = delete;

  /// Starts a UI frame: call before any ImGui:: widget calls.
  void beginFrame();
  /// Finishes the UI frame; the next Renderer::render() draws it.
  void endFrame();

 private:
  Renderer& m_renderer;
  VkDescriptorPool m_pool = VK_NULL_HANDLE;
};

}  // namespace vt::renderer
