#pragma once
// The HUD of a live session, shared by the desktop window and the headset's mirror window:
// builds the device/status lines and one touch line per contact from the TouchPipeline, draws
// every panel and applies the haptic settings the user changed. Main thread only, between
// ImGuiLayer begin/endFrame.
#include <string>

#include "modes/touch_pipeline.hpp"
#include "ui/hud.hpp"
#include "ui/recent_rate.hpp"

namespace vt::app {

/// Where interactive sessions keep the HUD layout: `$XDG_CONFIG_HOME/vtouching/imgui.ini`, else
/// `$HOME/.config/vtouching/imgui.ini` (the folder is created); empty when neither variable is
/// set or the folder cannot be made (then the layout is not kept, with an info line).
std::string hudSettingsFile();

class TouchHud {
 public:
  /// Installs the docked panel layout on the current ImGui context (before its first frame).
  /// `status` carries the fixed lines (scene, Vulkan device, OpenXR runtime, recording).
  /// `desktopControls`: the mouse/keyboard help applies (not in headset mode).
  TouchHud(const LoadedScene& scene, const HapticOptions& options, bool remote, ui::HudStatus status,
             bool desktopControls = true);

  /// Draws the panels (without them, only the desktop controls help where it applies).
  void draw(TouchPipeline& haptics, double frame_ms, bool panels = true);
  /// The OpenXR runtime and input source line (it changes when the runtime binds a profile).
  void setXrStatus(std::string text) { m_status.xrRuntime = std::move(text); }
  /// What the user set (the vibration-map overlay is read by the frame).
  const ui::HudSettings& settings() const { return m_settings; }
  /// The overlay's state at start (--overlay); the HUD's checkbox switches it afterwards.
  void setOverlay(bool on) { m_settings.overlay = on; }

 private:
  const LoadedScene& m_scene;
  ui::HudSettings m_settings;
  ui::HudStatus m_status;
  ui::RecentRate m_overruns, m_stalePoses;  // the loop's totals as recent rates
  bool m_desktopControls;
};

}  // namespace vt::app
