#pragma once
// The live haptic side of the desktop and headset modes: the pose channel, the haptic loop on
// its own thread, and its sinks (simulated or HID glove, recorder, XR controllers, UI).
// Main thread only, except poses() which the pose source (desktop input, OpenXR) writes.
#include <array>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "modes/haptic_options.hpp"
#include "modes/recording.hpp"
#include "modes/scene_source.hpp"
#include "vt/core/latest_value.hpp"
#include "vt/core/spsc_ring.hpp"
#include "vt/haptics/devices/glove_driver.hpp"
#include "vt/haptics/devices/sim_glove.hpp"
#include "vt/haptics/haptic_loop.hpp"

namespace vt::app {

enum class GloveKind { None, Simulated, Hid };

/// Reads --glove sim|hid|none.
GloveKind readGloveKind(cli::Args& args);

/// What the UI shows about one contact point (the newest trace plus a scrolling history).
struct ContactView {
  haptics::ContactTrace last;
  std::vector<float> history;  // intensity, one sample per kHistoryStep_ns, oldest first
};

class HapticSession {
 public:
  static constexpr int kHistory = 300;                      // samples in each UI plot
  static constexpr std::int64_t kHistoryStep_ns = 20'000'000;  // 50 Hz: a 6 s window

  /// Starts the loop and the glove driver. `recordPath` empty = no recording.
  HapticSession(const LoadedScene& scene, const SceneOptions& sceneOptions, HapticOptions options, GloveKind glove,
                const std::string& recordPath);
  ~HapticSession();

  /// The channel the haptic loop reads (one writer: the active pose source).
  LatestValue<HandPose>& poses() { return m_poses; }
  /// Publishes a pose from the main thread (and records it).
  void publishPose(const HandPose& pose);
  /// Records a pose some other writer published (headset mode), once per new version.
  void notePublishedPose();
  /// Restarts the loop with new settings (fresh renderer state; the recording notes it).
  void setOptions(const HapticOptions& options);
  const HapticOptions& options() const { return m_options; }
  /// Drains the trace and frame rings into the UI state and the recording. Call once per frame.
  void drain();
  /// Newest actuator frame the loop produced (also what the XR sink should play).
  const haptics::ActuatorFrame& lastFrame() const { return m_lastFrame; }
  const std::vector<ContactView>& contacts() const { return m_contacts; }
  const haptics::HapticConfig& config() const { return m_loop->config(); }
  haptics::LoopStats stats() const { return m_loop->stats(); }
  /// Ticks per second measured over the last second.
  double measuredRate_hz() const { return m_rate_hz; }
  /// Glove description and state for the HUD; empty when --glove none.
  std::string gloveStatus() const;
  /// The newest finger flexion the glove measured (false when there is no glove or no report yet).
  bool gloveFlexion(FingerCurls& out) const { return m_driver && m_driver->flexion().read(out); }
  /// The simulated glove's actuator levels (zeros without a simulated glove).
  std::array<float, haptics::kMaxActuators> gloveLevels() const;
  std::uint64_t droppedFrames() const { return m_frames.dropped() + m_traces.dropped(); }
  /// Stops the loop (silent frame to every sink), finishes the recording. Idempotent.
  void stop();

 private:
  void startLoop();

  const LoadedScene& m_scene;
  HapticOptions m_options;
  LatestValue<HandPose> m_poses;
  std::uint64_t m_recordedPoseVersion = 0;
  SpscRing<haptics::ActuatorFrame> m_frames{4096};
  SpscRing<haptics::ContactTrace> m_traces{16384};
  std::unique_ptr<haptics::glove::SimulatedGlove> m_simGlove;
  std::unique_ptr<haptics::glove::HidBackend> m_backend;
  std::unique_ptr<haptics::glove::GloveDriver> m_driver;
  std::unique_ptr<haptics::HapticLoop> m_loop;
  std::optional<SessionRecorder> m_recorder;
  std::vector<ContactView> m_contacts;
  std::vector<std::int64_t> m_nextHistory_ns;
  haptics::ActuatorFrame m_lastFrame;
  std::uint64_t m_rateTicks = 0;
  std::int64_t m_rateSince_ns = 0;
  double m_rate_hz = 0.0;
  bool m_stopped = false;
};

}  // namespace vt::app
