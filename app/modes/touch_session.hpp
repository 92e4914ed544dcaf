#pragma once
// The composition root: one "touch session" is everything between the hand and the actuators,
// assembled here for every mode (desktop, headset, client, serve, offscreen trajectories,
// replay) and the benchmarks: the scene, the pose history the input sources write, the
// tactile source (the haptic loop on its own thread, stepped by its owner, or a remote
// server's stream) and every sink (glove, recorders, UI rings, main-thread listeners such as
// the XR controllers). Adding a sink is one edit in TouchSession's constructor.
// Main thread only, except poses() (written by the one active input source, any thread).
#include <array>
#include <functional>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "modes/device_outputs.hpp"
#include "modes/haptic_options.hpp"
#include "modes/recording.hpp"
#include "modes/scene_source.hpp"
#include "vt/core/clock.hpp"
#include "vt/core/spsc_ring.hpp"
#include "vt/haptics/devices/glove_setup.hpp"
#include "vt/haptics/devices/recorder.hpp"
#include "vt/haptics/haptic_loop.hpp"
#include "vt/net/client.hpp"
#include "vt/scene/pose_history.hpp"

namespace vt::app {

/// Where the actuator output goes besides the UI.
struct HapticSinks {
  std::string glove = "sim";  // --glove sim|hid|hid:SERIAL|hid:/dev/hidrawN|none
  std::string record;         // --record FILE: poses + frames for `vtouching replay` (local loop only)
  std::string actuatorCsv;    // --record-csv FILE: every actuator frame as CSV
  std::string actuatorWav;    // --record-wav FILE: the actuator waveforms as a multichannel WAV
  OutputSpecs outputs;        // --output audio[:DEVICE] | osc://HOST:PORT, --channels (live loop only)
};

/// Reads --glove (default `defaultGlove`), --record, --record-csv, --record-wav, --output and --channels.
HapticSinks readHapticSinks(cli::Args& args, const char* defaultGlove = "sim");

/// Who makes the actuator frames.
enum class TouchDrive {
  LoopThread,  // live: the haptic loop's own fixed-rate thread (desktop, headset)
  Stepped,     // tick(t) by the owner (offscreen runs, replays, benchmarks) or by net::Server at each pose
  Remote,      // client mode: a remote tactile server; its decoded stream feeds the sinks
};

/// Everything a mode says about its touch pipeline.
struct TouchSessionSpec {
  SceneOptions sceneOptions;  // what the recording header names
  HapticOptions haptic;
  HapticSinks sinks;
  TouchDrive drive = TouchDrive::LoopThread;
  std::optional<net::ClientConfig> remote;  // TouchDrive::Remote
  const Clock* clock = &SteadyClock::instance();
};

/// What the UI shows about one contact point (the newest trace plus a scrolling history).
struct ContactView {
  haptics::ContactTrace last;
  std::vector<float> history;  // intensity, one sample per kHistoryStep_ns, oldest first
};

class TouchSession {
 public:
  static constexpr int kHistory = 300;                         // samples in each UI plot
  static constexpr std::int64_t kHistoryStep_ns = 20'000'000;  // 50 Hz: a 6 s window

  /// Builds and starts the whole pipeline (throws vt::Error naming the part that failed,
  /// e.g. a refused remote session or a glove that is not there).
  TouchSession(const LoadedScene& scene, TouchSessionSpec spec);
  ~TouchSession();
  TouchSession(const TouchSession&) = delete;
  TouchSession& operator=(const TouchSession&) = delete;

  /// The pose history: the one input source writes it (any one thread), the loop samples it.
  PoseHistory& poses() { return *m_poses; }
  /// Publishes a pose stamped with the time it describes; `jump`: a reset, not motion.
  void publishPose(const HandPose& pose, bool jump = false) { m_poses->publish(pose, jump); }
  /// TouchDrive::Stepped: one tick at t_ns (false in the other drives).
  bool tick(std::int64_t t_ns);
  /// The local haptic loop (null in client mode).
  haptics::HapticLoop* loop() { return m_loop.get(); }

  /// Main-thread consumers of every frame and trace, called from drain().
  void onFrame(std::function<void(const haptics::ActuatorFrame&)> listener);
  void onTrace(std::function<void(const haptics::ContactTrace&)> listener);
  /// Drains the rings into the UI state, the recordings and the listeners. Main thread, often.
  void drain();

  /// Restarts the loop with new settings (fresh renderer state; the recording notes it).
  /// In client mode the server's settings apply: ignored, with one log line.
  void setOptions(const HapticOptions& options);
  const HapticOptions& options() const { return m_options; }
  const haptics::HapticConfig& config() const { return m_config; }
  /// Client mode: the network session (null with the local loop).
  const net::Client* client() const { return m_client.get(); }
  /// One line for the HUD: the network session's state, or that there is none.
  std::string networkStatus() const;
  /// Newest actuator frame.
  const haptics::ActuatorFrame& lastFrame() const { return m_lastFrame; }
  const std::vector<ContactView>& contacts() const { return m_contacts; }
  /// The local loop's statistics (zeros in client mode).
  haptics::LoopStats stats() const { return m_loop ? m_loop->stats() : haptics::LoopStats{}; }
  /// Ticks (client mode: frames played) per second, measured over the last second; NaN during
  /// the first second (not measured yet, unlike a loop that stopped: 0).
  double measuredRate_hz() const { return m_rate_hz; }
  /// Poses per second arriving in the history, measured over the last second (NaN at first).
  double poseRate_hz() const { return m_poseRate_hz; }
  /// The hand the renderer drew (stamped with the time it shows): compared with the contact
  /// point the haptic loop used for the same time. Main thread.
  void noteDrawnHand(const HandPose& drawn);
  /// Drawn-versus-felt fingertip distance over the recent frames (mm; 0 before any match).
  double drawnVersusFelt_mm_p50() const;
  double drawnVersusFelt_mm_max() const;
  /// One HUD line: pose rate and age, the sampling mode, drawn-versus-felt distance.
  std::string timingStatus() const;
  /// Glove description and state for the HUD; "none" without a glove.
  std::string gloveStatus() const;
  /// The --output sinks' state for the HUD; empty without any.
  std::string outputsStatus() const { return m_outputs ? m_outputs->status() : std::string(); }
  /// The newest finger flexion the glove measured (false when there is no glove or no report yet).
  bool gloveFlexion(FingerCurls& out) const { return m_glove && m_glove->driver().flexion().read(out); }
  /// The glove's flexion channel (any thread may read it), or nullptr when there is no glove.
  const LatestValue<FingerCurls>* gloveFlexionChannel() const {
    return m_glove ? &m_glove->driver().flexion() : nullptr;
  }
  /// The simulated glove's actuator levels (the last frame's levels without a simulated glove).
  std::array<float, haptics::kMaxActuators> gloveLevels() const;
  /// Frames, traces or poses the main thread could not keep (the recording then differs).
  std::uint64_t droppedRecords() const { return m_frames.dropped() + m_traces.dropped() + m_posesMissed; }
  /// Stops the source (silent frame to every sink), the glove, finishes the recordings. Idempotent.
  void stop();

 private:
  void startLoop();
  void connect(net::ClientConfig config);
  void resetViews(std::size_t count);
  void recordPoses();
  void noteFrameLevels(const haptics::ActuatorFrame& frame);
  void updateRates(std::int64_t now_ns);

  const LoadedScene& m_scene;
  TouchSessionSpec m_spec;
  HapticOptions m_options;
  haptics::HapticConfig m_config;
  std::unique_ptr<PoseHistory> m_poses = std::make_unique<PoseHistory>();
  SpscRing<haptics::ActuatorFrame> m_frames{4096};
  SpscRing<haptics::ContactTrace> m_traces{16384};
  std::unique_ptr<haptics::glove::GloveSetup> m_glove;
  std::optional<DeviceOutputs> m_outputs;  // --output: audio interfaces, OSC (TouchDrive::LoopThread)
  std::unique_ptr<haptics::HapticLoop> m_loop;  // local drives
  std::unique_ptr<net::Client> m_client;        // TouchDrive::Remote
  net::Endpoint m_server;
  bool m_reconnecting = false;  // the client resumes by itself after the server went away
  std::optional<SessionRecorder> m_recorder;
  std::uint64_t m_posesRecorded = 0, m_posesMissed = 0;
  std::uint32_t m_recordedSegment = 0;
  std::optional<haptics::ActuatorRecorder> m_actuatorRecorder;
  std::vector<std::function<void(const haptics::ActuatorFrame&)>> m_frameListeners;
  std::vector<std::function<void(const haptics::ContactTrace&)>> m_traceListeners;
  struct TimedTip {
    std::int64_t t_ns = 0;
    glm::vec3 tip_m{0.0f};
  };
  static constexpr std::size_t kTipWindow = 512;
  std::size_t m_feltContact = 0;          // the contact point compared (the index fingertip)
  std::vector<TimedTip> m_felt;           // its recent haptic samples (ring of kTipWindow)
  std::size_t m_feltNext = 0;
  std::vector<TimedTip> m_drawn;          // drawn tips waiting for the haptic sample of their time
  std::vector<float> m_offsets_mm;        // recent matched distances (ring of kTipWindow)
  std::size_t m_offsetNext = 0;
  void matchDrawnHands();
  std::vector<ContactView> m_contacts;
  std::vector<std::int64_t> m_nextHistory_ns;
  haptics::ActuatorFrame m_lastFrame;
  std::uint64_t m_framesPlayed = 0;  // frames drained (client mode's rate)
  std::uint64_t m_rateTicks = 0, m_ratePoses = 0;
  std::int64_t m_rateSince_ns = 0;
  double m_rate_hz = std::numeric_limits<double>::quiet_NaN(), m_poseRate_hz = std::numeric_limits<double>::quiet_NaN();
  bool m_stopped = false;
};

}  // namespace vt::app
