#pragma once
// The live haptic side of the desktop and headset modes: the pose channel, the tactile source
// and its sinks (simulated or HID glove, recorders, XR controllers, UI). The source is the
// haptic loop on its own thread, or in client mode (`vtouching client`) a remote tactile
// server: a forwarding thread sends the newest pose at the session's block rate and the
// decoded stream feeds the same sinks. Main thread only, except poses() which the pose
// source (desktop input, OpenXR, a trajectory) writes.
#include <array>
#include <atomic>
#include <memory>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "modes/haptic_options.hpp"
#include "modes/recording.hpp"
#include "modes/scene_source.hpp"
#include "vt/core/latest_value.hpp"
#include "vt/core/spsc_ring.hpp"
#include "vt/haptics/devices/glove_driver.hpp"
#include "vt/haptics/devices/recorder.hpp"
#include "vt/haptics/devices/sim_glove.hpp"
#include "vt/haptics/haptic_loop.hpp"
#include "vt/net/client.hpp"

namespace vt::app {

enum class GloveKind { None, Simulated, Hid };

/// Where the actuator output goes besides the UI.
struct HapticSinks {
  GloveKind glove = GloveKind::Simulated;
  std::string record;       // --record FILE: poses + frames for `vtouching replay` (local loop only)
  std::string actuatorCsv;  // --record-csv FILE: every actuator frame as CSV
  std::string actuatorWav;  // --record-wav FILE: the actuator waveforms as a multichannel WAV
};

/// Reads --glove sim|hid|none, --record, --record-csv and --record-wav.
HapticSinks readHapticSinks(cli::Args& args);

/// What the UI shows about one contact point (the newest trace plus a scrolling history).
struct ContactView {
  haptics::ContactTrace last;
  std::vector<float> history;  // intensity, one sample per kHistoryStep_ns, oldest first
};

class HapticSession {
 public:
  static constexpr int kHistory = 300;                      // samples in each UI plot
  static constexpr std::int64_t kHistoryStep_ns = 20'000'000;  // 50 Hz: a 6 s window

  /// Starts the glove driver and the tactile source: the local loop, or with `remote` a session
  /// with that server (its sceneDigest is set from `scene`; throws vt::Error when refused).
  HapticSession(const LoadedScene& scene, const SceneOptions& sceneOptions, HapticOptions options,
                const HapticSinks& sinks, std::optional<net::ClientConfig> remote = std::nullopt);
  ~HapticSession();

  /// The channel the haptic loop reads (one writer: the active pose source).
  LatestValue<HandPose>& poses() { return m_poses; }
  /// Publishes a pose from the main thread (and records it).
  void publishPose(const HandPose& pose);
  /// Records a pose some other writer published (headset mode), once per new version.
  void notePublishedPose();
  /// Restarts the loop with new settings (fresh renderer state; the recording notes it).
  /// In client mode the server's settings apply: ignored, with one log line.
  void setOptions(const HapticOptions& options);
  /// Client mode: the network session (null with the local loop).
  const net::Client* client() const { return m_client.get(); }
  /// One line for the HUD: the network session's state, or that there is none.
  std::string networkStatus() const;
  const HapticOptions& options() const { return m_options; }
  /// Drains the trace and frame rings into the UI state and the recording. Call once per frame.
  void drain();
  /// Newest actuator frame the loop produced (also what the XR sink should play).
  const haptics::ActuatorFrame& lastFrame() const { return m_lastFrame; }
  const std::vector<ContactView>& contacts() const { return m_contacts; }
  const haptics::HapticConfig& config() const { return m_config; }
  /// The local loop's statistics (zeros in client mode).
  haptics::LoopStats stats() const { return m_loop ? m_loop->stats() : haptics::LoopStats{}; }
  /// Ticks (client mode: frames played) per second, measured over the last second.
  double measuredRate_hz() const { return m_rate_hz; }
  /// Glove description and state for the HUD; empty when --glove none.
  std::string gloveStatus() const;
  /// The newest finger flexion the glove measured (false when there is no glove or no report yet).
  bool gloveFlexion(FingerCurls& out) const { return m_driver && m_driver->flexion().read(out); }
  /// The glove's flexion channel (any thread may read it), or nullptr when there is no glove.
  const LatestValue<FingerCurls>* gloveFlexionChannel() const { return m_driver ? &m_driver->flexion() : nullptr; }
  /// The simulated glove's actuator levels (zeros without a simulated glove).
  std::array<float, haptics::kMaxActuators> gloveLevels() const;
  std::uint64_t droppedFrames() const { return m_frames.dropped() + m_traces.dropped(); }
  /// Stops the loop or the network session (silent frame to every sink), finishes the
  /// recordings. Idempotent.
  void stop();

 private:
  void startLoop();
  void connect(net::ClientConfig config);
  void forwardPoses() noexcept;
  void noteFrameLevels(const haptics::ActuatorFrame& frame);
  void updateRate(std::int64_t now_ns);

  const LoadedScene& m_scene;
  HapticOptions m_options;
  haptics::HapticConfig m_config;
  LatestValue<HandPose> m_poses;
  std::uint64_t m_recordedPoseVersion = 0;
  SpscRing<haptics::ActuatorFrame> m_frames{4096};
  SpscRing<haptics::ContactTrace> m_traces{16384};
  std::unique_ptr<haptics::glove::SimulatedGlove> m_simGlove;
  std::unique_ptr<haptics::glove::HidBackend> m_backend;
  std::unique_ptr<haptics::glove::GloveDriver> m_driver;
  std::unique_ptr<haptics::HapticLoop> m_loop;                  // local mode
  std::unique_ptr<net::Client> m_client;                        // client mode
  net::Endpoint m_server;
  bool m_reconnecting = false;  // the client resumes by itself after the server went away
  std::thread m_forwarder;                                      // client mode: pose sender
  std::atomic<bool> m_forwarding{false};
  std::optional<SessionRecorder> m_recorder;
  std::optional<haptics::ActuatorRecorder> m_actuatorRecorder;
  std::vector<ContactView> m_contacts;
  std::vector<std::int64_t> m_nextHistory_ns;
  haptics::ActuatorFrame m_lastFrame;
  std::uint64_t m_framesPlayed = 0;  // frames drained (client mode's rate)
  std::uint64_t m_rateTicks = 0;
  std::int64_t m_rateSince_ns = 0;
  double m_rate_hz = 0.0;
  bool m_stopped = false;
};

}  // namespace vt::app
