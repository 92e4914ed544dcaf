#pragma once
// The desktop HUD in Dear ImGui: what each finger touches, scrolling intensity plots, haptic
// settings, device status with frame time and haptic rate, the simulated glove's actuators on a
// hand diagram, and the controls help. Main thread only, between ImGuiLayer begin/endFrame.
#include <array>
#include <string>
#include <vector>

#include "modes/haptic_options.hpp"
#include "vt/haptics/actuator_frame.hpp"
#include "vt/haptics/haptic_loop.hpp"

namespace vt::ui {

/// Device and timing lines (strings prepared by the mode).
struct HudStatus {
  std::string scene;
  std::string vulkanDevice;
  std::string xrRuntime;
  std::string glove;
  std::string outputs;   // audio / OSC sinks, empty = none
  std::string realtime;  // what each real-time thread was granted (vt::describeRealtimeGrants)
  std::string network = "off (vtouching serve / client)";
  bool remote = false;  // client mode: the haptic loop runs on the server
  double frame_ms = 0.0;
  double hapticRate_hz = 0.0;
  haptics::LoopStats loop;  // its overruns and stale poses are totals since the loop started
  double overrunRate_hz = 0.0;    // over the last seconds (RecentRate): what the panel shows
  double stalePoseRate_hz = 0.0;
  std::uint64_t droppedRecords = 0;
  std::string timing;     // pose rate and age, sampling mode, felt latency, display lag
  std::string consistency;  // the consistency meter: drawn against felt contact, frozen ticks, stops
  std::string recording;  // empty = not recording
};

/// One contact point's line in the touch panel.
struct HudContact {
  int finger = 1;  // thumb = 0 .. little = 4 (colour and name)
  bool inContact = false;
  std::string material;
  float u = 0.0f, v = 0.0f, depth_m = 0.0f, intensity = 0.0f;
  float acrossWeight = -1.0f;  // direction blend: share of the across-scanned map; < 0: one map only
  const std::vector<float>* history = nullptr;  // oldest first
};

/// Settings the user edits; the mode applies them when drawHud returns true.
struct HudSettings {
  app::HapticOptions haptic;  // the one form of the haptic settings (the mode's, then the user's)
  bool overlay = false;
  bool help = true;
  bool editable = true;  // false in client mode: the tactile settings are the server's
};

inline constexpr std::array<int, 4> kRates = {250, 500, 1000, 2000};

/// Draws every panel; true when a haptic setting (model, gain, rate, mapping, sampling) changed.
bool drawHud(const HudStatus& status, const std::vector<HudContact>& contacts,
             const std::array<float, haptics::kMaxActuators>& gloveLevels, HudSettings& settings);

/// The controls, as a semi-transparent overlay in the bottom-left corner.
void drawHelpOverlay();
/// A measured rate as "995 Hz", or "-- Hz" while not measured yet (NaN).
std::string rateText(double rate_hz);

}  // namespace vt::ui
