#pragma once
// The composition root: one "touch pipeline" is everything between the hand and the actuators,
// assembled here for every mode (desktop, headset, client, serve, offscreen trajectories,
// replay) and the benchmarks: the scene, the pose history the input sources write, the frame
// source (the haptic loop on its own thread, stepped by its owner or by the network server, or
// a remote server's stream) and every output. Outputs are haptics::ActuatorSinks, attached only
// here: the glove, audio interfaces and OSC (--output), the recorders, the network stream the
// server sends, and the sinks a mode brings (the XR controllers). The felt outputs' declared
// latencies set the loop's timing and the consistency meter's felt moment.
// Main thread only, except poses() (written by the one active input source, any thread).
#include <array>
#include <functional>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "modes/consistency_meter.hpp"
#include "modes/device_outputs.hpp"
#include "modes/haptic_options.hpp"
#include "modes/recording.hpp"
#include "modes/scene_source.hpp"
#include "vt/core/clock.hpp"
#include "vt/core/spsc_ring.hpp"
#include "vt/haptics/actuator_sink.hpp"
#include "vt/haptics/devices/glove_setup.hpp"
#include "vt/haptics/haptic_loop.hpp"
#include "vt/net/client.hpp"
#include "vt/net/server.hpp"
#include "vt/scene/pose_history.hpp"

namespace vt::app {

/// Where the actuator output goes besides the UI.
struct HapticSinks {
  std::string glove = "sim";  // --glove sim|hid|hid:SERIAL|hid:/dev/hidrawN|none
  std::string record;         // --record FILE: poses + frames for `vtouching replay` (local loop only)
  std::string actuatorCsv;    // --record-csv FILE: every actuator frame as CSV
  std::string actuatorWav;    // --record-wav FILE: the actuator waveforms as a multichannel WAV
  OutputSpecs outputs;        // --output audio[:DEVICE] | osc://HOST:PORT, --channels (live sources)
};

/// Reads --glove (default `defaultGlove`), --record, --record-csv, --record-wav, --output and --channels.
HapticSinks readHapticSinks(cli::Args& args, const char* defaultGlove = "sim");

/// Who makes the actuator frames.
enum class TouchDrive {
  LoopThread,  // live: the haptic loop's own fixed-rate thread (desktop, headset)
  Stepped,     // tick(t) by the owner (offscreen runs, replays, benchmarks)
  Served,      // the network server built here ticks the loop at each received pose's time (serve)
  Remote,      // a remote tactile server; its decoded stream feeds the sinks (client)
};

/// Everything a mode says about its touch pipeline.
struct TouchPipelineSpec {
  SceneOptions sceneOptions;  // what the recording header names
  HapticOptions haptic;
  HapticSinks sinks;
  TouchDrive drive = TouchDrive::LoopThread;
  std::optional<net::ClientConfig> remote;  // TouchDrive::Remote
  std::optional<net::ServerConfig> served;  // TouchDrive::Served (its tick, poses and format are set here)
  const Clock* clock = &SteadyClock::instance();
};

/// What the UI shows about one contact point (the newest trace plus a scrolling history).
struct ContactView {
  haptics::ContactTrace last;
  std::vector<float> history;  // intensity, one sample per kHistoryStep_ns, oldest first
};

class TouchPipeline {
 public:
  static constexpr int kHistory = 300;                         // samples in each UI plot
  static constexpr std::int64_t kHistoryStep_ns = 20'000'000;  // 50 Hz: a 6 s window

  /// Builds and starts the whole pipeline (throws vt::Error naming the part that failed,
  /// e.g. a refused remote session or a glove that is not there).
  TouchPipeline(const LoadedScene& scene, TouchPipelineSpec spec);
  ~TouchPipeline();
  TouchPipeline(const TouchPipeline&) = delete;
  TouchPipeline& operator=(const TouchPipeline&) = delete;

  /// The pose history: the one input source writes it (any one thread), the loop samples it.
  PoseHistory& poses() { return *m_poses; }
  /// Publishes a pose stamped with the time it describes; `jump`: a reset, not motion.
  void publishPose(const HandPose& pose, bool jump = false) { m_poses->publish(pose, jump); }
  /// TouchDrive::Stepped: one tick at t_ns (false in the other drives); with `hand_t_ns`, the
  /// hand is rendered at exactly that time (a replay of a recorded tick).
  bool tick(std::int64_t t_ns, std::optional<std::int64_t> hand_t_ns = std::nullopt);
  /// The local haptic loop (null in client mode).
  haptics::HapticLoop* loop() { return m_loop.get(); }
  const haptics::HapticLoop* loop() const { return m_loop.get(); }
  /// TouchDrive::Served: the network server (null in the other drives).
  net::Server* server() { return m_server.get(); }

  /// Attaches a main-thread sink a mode brings (the XR controllers); realtime sinks come from
  /// the pipeline's options. The pipeline owns it; the reference stays valid until the pipeline ends.
  haptics::ActuatorSink& attach(std::unique_ptr<haptics::ActuatorSink> sink);
  /// Every attached output, in the order attached.
  const std::vector<std::unique_ptr<haptics::ActuatorSink>>& sinks() const { return m_sinks; }
  /// The felt outputs' latency the loop renders ahead by (their largest, plus --haptic-latency-ms).
  std::int64_t feltLatency_ns() const { return m_feltLatency_ns; }
  /// How old the hand the display shows is when it is shown (the display's input-to-photon lag):
  /// the loop renders the hand as it will be seen when felt (docs/tactile-rendering.md, "Time").
  void setDisplayLag(std::int64_t lag_ns);
  /// The display lag the felt side plays for now: the one set, once a change has been slewed in
  /// (the display presents at it, app/modes/present_pacer.hpp). The thread that calls drain().
  std::int64_t feltDisplayLag_ns() const;

  /// Main-thread consumers of every frame and trace, called from drain().
  void onFrame(std::function<void(const haptics::ActuatorFrame&)> listener);
  void onTrace(std::function<void(const haptics::ContactTrace&)> listener);
  /// Drains the rings into the UI state, the main-thread sinks and the listeners. Main thread, often.
  void drain();

  /// Restarts the loop with new settings (fresh tactile model state; the recording notes it).
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

  /// A displayed frame: the hand drawn (its pose stamped with the time it shows) and when it is
  /// shown. The consistency meter compares it with what the felt outputs play then; recorded. Main thread.
  void noteDrawnFrame(const HandPose& drawn, std::int64_t display_t_ns);
  /// What the consistency meter measured so far (client mode: nothing, contacts are the server's).
  ConsistencyReport consistency() const { return m_meter ? m_meter->report() : ConsistencyReport{}; }
  /// One HUD line: pose rate and age, the sampling mode, the felt latency and display lag.
  std::string timingStatus() const;
  /// One HUD line: the consistency meter's figures (refreshed once a second).
  const std::string& consistencyStatus() const { return m_consistencyLine; }
  /// Glove description and state for the HUD; "none" without a glove.
  std::string gloveStatus() const { return m_glove ? m_glove->statusLine() : "none"; }
  /// The other outputs' state for the HUD; empty without any.
  std::string outputsStatus() const;
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
  /// Stops the source (silent frame to every sink), every sink, finishes the recordings. Idempotent.
  void stop();

 private:
  haptics::ActuatorSink& own(std::unique_ptr<haptics::ActuatorSink> sink);
  void startLoop();
  void connect(net::ClientConfig config);
  void serve(net::ServerConfig config);
  void resetViews(std::size_t count);
  void readPoses();
  void noteFrameLevels(const haptics::ActuatorFrame& frame);
  void notePlayedFrame(const haptics::ActuatorFrame& frame);
  void updateHandLead();
  void updateRates(std::int64_t now_ns);
  void updateFeltLatency();

  const LoadedScene& m_scene;
  TouchPipelineSpec m_spec;
  HapticOptions m_options;
  haptics::HapticConfig m_config;
  std::unique_ptr<PoseHistory> m_poses = std::make_unique<PoseHistory>();
  // Every frame and trace, for the main thread, held while it is away (a slow frame): at the
  // default 1 kHz loop the frames last 4 s, as long as the pose history keeps a 1 kHz input, and
  // the traces (five contacts a tick) 3.3 s; a 4 kHz loop fills both four times sooner. What
  // overflows is counted (droppedRecords) and logged with the recording.
  SpscRing<haptics::ActuatorFrame> m_frames{PoseHistory::kCapacity};
  SpscRing<haptics::ContactTrace> m_traces{16384};
  SpscRing<haptics::ActuatorFrame> m_streamFrames{4};  // Served: the frame each pose-driven tick made
  std::vector<std::unique_ptr<haptics::ActuatorSink>> m_sinks;
  haptics::glove::GloveSetup* m_glove = nullptr;      // one of m_sinks
  ReplayRecorder* m_recorder = nullptr;              // one of m_sinks
  haptics::ActuatorSink* m_actuatorRecorder = nullptr;  // one of m_sinks (--record-csv/--record-wav)
  std::unique_ptr<haptics::HapticLoop> m_loop;  // local drives
  std::unique_ptr<net::Client> m_client;        // TouchDrive::Remote
  std::unique_ptr<net::Server> m_server;        // TouchDrive::Served
  net::Endpoint m_remoteServer;
  bool m_reconnecting = false;  // the client resumes by itself after the server went away
  std::optional<ConsistencyMeter> m_meter;
  std::int64_t m_feltLatency_ns = 0;
  std::int64_t m_displayLag_ns = 0;
  // Client mode: recent stream delays (a pose sent -> its frame played), for the hand lead: 64 ms
  // of frames, so a move of the playout schedule is followed within a frame or two of the window.
  std::array<std::int64_t, 16> m_streamDelays{};
  std::size_t m_streamDelayCount = 0;
  std::int64_t m_feltAfterSend_ns = 0;  // client mode: the median stream delay + the felt latency
  std::uint64_t m_posesRead = 0, m_posesMissed = 0;
  std::int64_t m_newestPoseRead_ns = 0;
  std::uint32_t m_poseSegment = 0;
  std::vector<std::function<void(const haptics::ActuatorFrame&)>> m_frameListeners;
  std::vector<std::function<void(const haptics::ContactTrace&)>> m_traceListeners;
  std::vector<ContactView> m_contacts;
  std::vector<std::int64_t> m_nextHistory_ns;
  haptics::ActuatorFrame m_lastFrame;
  std::uint64_t m_framesPlayed = 0;  // frames drained (client mode's rate)
  std::uint64_t m_rateTicks = 0, m_ratePoses = 0;
  std::int64_t m_rateSince_ns = 0;
  double m_rate_hz = std::numeric_limits<double>::quiet_NaN(), m_poseRate_hz = std::numeric_limits<double>::quiet_NaN();
  std::string m_consistencyLine = "measuring";
  bool m_stopped = false;
};

}  // namespace vt::app
