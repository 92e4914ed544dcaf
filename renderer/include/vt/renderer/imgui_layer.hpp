#pragma once
// Dear ImGui on a window target: the window's input events (WindowTarget::takeUiEvents) and
// Vulkan drawing inside the renderer's own render pass (through Renderer::setPassHook), so UI
// panels cost no extra pass. The thread that renders the window (the UI thread) only, except
// wantsMouse()/wantsKeyboard().
// The window's attachment is sRGB, so ImGui colours are linear: the layer converts its style;
// give custom widget colours in linear RGB too.
#include <array>
#include <atomic>
#include <cstdint>
#include <memory>
#include <string>

#include "vt/renderer/renderer.hpp"
#include "vt/renderer/window_target.hpp"
#include "vt/scene/image.hpp"

struct ImGuiStyle;

namespace vt::renderer {

class ImGuiImages;

/// The UI text size for a window `height_px` high (window coordinates) over ImGui's 13 px font:
/// 1 up to 899 px, then in quarter steps with the height (1080p: 1.5, 1440p: 2, 2160p: 3).
float textScaleForHeight(int height_px) noexcept;

/// Owns the ImGui context, its input from the window's events and its Vulkan backend. One per process.
class ImGuiLayer {
 public:
  /// Creates the context, uploads the font and installs the pass hook on `renderer`.
  /// Both must outlive this object.
  ImGuiLayer(Renderer& renderer, WindowTarget& window);
  ~ImGuiLayer();
  ImGuiLayer(const ImGuiLayer&) = delete;
  ImGuiLayer& operator=(const ImGuiLayer&) = delete;

  /// Keeps the panels' layout in `path` (ImGui's ini file: read at the first frame, written when
  /// it changes and at exit); empty = nowhere (the default). Call before the first beginFrame;
  /// the folder must exist.
  void setSettingsFile(std::string path);

  /// Starts a UI frame with the window events since the last one: call before any ImGui:: widget
  /// calls. When the window's height asks for another text size (textScaleForHeight) the font
  /// and the style's sizes are rebuilt first.
  void beginFrame();
  /// The text scale in use (1 = ImGui's 13 px font).
  float textScale() const { return m_textScale; }
  /// Finishes the UI frame; the next Renderer::render() draws it.
  void endFrame();
  /// Whether the last UI frame wanted the mouse / keyboard (over a panel, typing): the input
  /// handling leaves them to the UI then. Any thread.
  bool wantsMouse() const { return m_wantsMouse.load(std::memory_order_relaxed); }
  bool wantsKeyboard() const { return m_wantsKeyboard.load(std::memory_order_relaxed); }

  /// Uploads an RGBA8 (sRGB-encoded) image into image slot 0..3; the GPU image is reused while
  /// the size stays the same. Main thread, between frames or inside one. Throws vt::Error on a
  /// bad slot or image.
  void setImage(std::uint32_t slot, const Image8& rgba);
  /// Inside a UI frame: an item of the given size (pixels) showing the slot's image in the
  /// current ImGui window (blank space before the first setImage).
  void image(std::uint32_t slot, float width_px, float height_px);

 private:
  static constexpr int kButtons = 5;
  void applyEvents();
  /// (Re)builds the font at 13 px x `scale`, uploads it and scales the style. No frame in flight.
  void buildFont(float scale);

  Renderer& m_renderer;
  WindowTarget& m_window;
  float m_textScale = 0.0f;  // none built yet
  std::unique_ptr<ImGuiStyle> m_baseStyle;  // the style at scale 1
  std::unique_ptr<ImGuiImages> m_images;
  std::array<bool, kButtons> m_releaseNextFrame{};
  std::int64_t m_lastFrame_ns = 0;
  std::atomic<bool> m_wantsMouse{false}, m_wantsKeyboard{false};
  VkDescriptorPool m_pool = VK_NULL_HANDLE;
  std::string m_settingsFile;  // ImGui keeps a pointer to it
};

}  // namespace vt::renderer
