#include "modes/haptic_session.hpp"

#include <algorithm>
#include <cstdio>

#include "vt/core/error.hpp"
#include "vt/core/log.hpp"
#include "vt/core/realtime.hpp"
#include "vt/haptics/devices/sim_transport.hpp"

namespace vt::app {

namespace {
constexpr int kHapticThreadPriority = 20;
}  // namespace

HapticSinks readHapticSinks(cli::Args& args) {
  HapticSinks sinks;
  const std::string glove = args.valueOr("glove", "sim");
  if (glove == "sim") sinks.glove = GloveKind::Simulated;
  else if (glove == "hid") sinks.glove = GloveKind::Hid;
  else if (glove == "none") sinks.glove = GloveKind::None;
  else fail(args.command(), ": --glove '", glove, "' is not sim|hid|none");
  sinks.record = args.valueOr("record", "");
  sinks.actuatorCsv = args.valueOr("record-csv", "");
  sinks.actuatorWav = args.valueOr("record-wav", "");
  return sinks;
}

HapticSession::HapticSession(const LoadedScene& scene, const SceneOptions& sceneOptions, HapticOptions options,
                             const HapticSinks& sinks, std::optional<net::ClientConfig> remote)
    : m_scene(scene), m_options(options), m_config(makeHapticConfig(options)) {
  if (!sinks.record.empty()) {
    // A replay re-runs the local loop; a remote server's output cannot be reproduced from poses.
    if (remote) fail("--record replays the local haptic loop; in client mode record with --record-csv/--record-wav");
    m_recorder.emplace(sinks.record, sceneOptions, options);
  }
  if (sinks.glove == GloveKind::Simulated) {
    m_simGlove = std::make_unique<haptics::glove::SimulatedGlove>(SteadyClock::instance());
    m_backend = std::make_unique<haptics::glove::SimGloveBackend>(*m_simGlove);
  } else if (sinks.glove == GloveKind::Hid) {
    m_backend = haptics::glove::makeHidapiBackend();
  }
  if (m_backend) m_driver = std::make_unique<haptics::glove::GloveDriver>(*m_backend, haptics::glove::GloveDriverConfig{});
  if (remote) connect(std::move(*remote));
  else startLoop();
  if (!sinks.actuatorCsv.empty() || !sinks.actuatorWav.empty()) {
    const int channels = m_client ? m_client->session().actuatorCount : m_config.actuatorCount();
    m_actuatorRecorder.emplace(sinks.actuatorCsv, sinks.actuatorWav, channels);
  }
}

HapticSession::~HapticSession() {
  try {
    stop();
  } catch (const Error& e) {
    log::error(e.what());
  }
}

void HapticSession::startLoop() {
  haptics::HapticConfig config = m_config;
  // The live loop asks for SCHED_FIFO (granted to root / CAP_SYS_NICE): period jitter drops
  // from milliseconds to tens of microseconds on a busy machine (docs/PERFORMANCE.md).
  config.realtimePriority = kHapticThreadPriority;
  m_loop = std::make_unique<haptics::HapticLoop>(config, m_poses);
  m_loop->addOutput(m_frames);
  if (m_driver) m_loop->addOutput(m_driver->mailbox());
  m_loop->setTraceOutput(m_traces);
  m_loop->publishScene(m_scene.haptic);
  m_contacts.assign(m_loop->config().contacts.size(), ContactView{});
  for (auto& c : m_contacts) c.history.assign(kHistory, 0.0f);
  m_nextHistory_ns.assign(m_contacts.size(), 0);
  m_rateTicks = 0;
  m_rateSince_ns = SteadyClock::instance().now_ns();
  m_loop->start();
}

void HapticSession::connect(net::ClientConfig config) {
  config.sceneDigest = tactileDigest(*m_scene.scene);
  // The network thread plays the stream out: it is this side's haptic thread.
  config.realtimePriority = kHapticThreadPriority;
  m_server = config.server;
  m_reconnecting = config.reconnect;
  config.framesOut = &m_frames;
  config.latestOut = m_driver ? &m_driver->mailbox() : nullptr;
  m_client = std::make_unique<net::Client>(std::move(config));
  m_client->connect();
  // The HUD shows one line per actuator of the server's stream (named after this side's mapping).
  const std::size_t actuators = std::min<std::size_t>(m_client->session().actuatorCount, m_config.contacts.size());
  m_contacts.assign(actuators, ContactView{});
  for (auto& c : m_contacts) c.history.assign(kHistory, 0.0f);
  m_nextHistory_ns.assign(m_contacts.size(), 0);
  m_rateSince_ns = SteadyClock::instance().now_ns();
  m_forwarding.store(true);
  m_forwarder = std::thread([this] { forwardPoses(); });
}

void HapticSession::forwardPoses() noexcept {
  // Poses leave at the stream's block rate whatever the input rate (a window or a headset runs
  // at its display rate): the server renders one block per pose, so the stream never starves.
  // Each is stamped when sent: the measured latency runs from here to the actuator output.
  requestRealtimePriority(kHapticThreadPriority);  // late sends widen the server's arrival spread
  const Clock& clock = SteadyClock::instance();
  const net::Accept& session = m_client->session();
  const std::int64_t period_ns = std::int64_t(session.blockLength) * 1'000'000'000 / std::int64_t(session.sampleRate_hz);
  std::int64_t next = clock.now_ns();
  std::uint64_t sequence = 0;
  HandPose pose;
  while (m_forwarding.load(std::memory_order_acquire)) {
    next += period_ns;
    clock.sleepUntil(next);
    const std::int64_t now = clock.now_ns();
    if (now - next > period_ns) next = now;  // fell behind (a stall): no burst to catch up
    if (!m_poses.read(pose)) continue;  // no hand yet
    pose.t_ns = now;
    pose.sequence = ++sequence;
    m_client->sendPose(pose);  // false once the session is over: the HUD says so
  }
}

void HapticSession::publishPose(const HandPose& pose) {
  m_poses.publish(pose);
  m_recordedPoseVersion = m_poses.version();
  if (m_recorder) m_recorder->pose(pose);
}

void HapticSession::notePublishedPose() {
  if (!m_recorder || m_poses.version() == m_recordedPoseVersion) return;
  HandPose pose;
  if (m_poses.read(pose)) m_recorder->pose(pose);
  m_recordedPoseVersion = m_poses.version();
}

void HapticSession::setOptions(const HapticOptions& options) {
  if (m_client) {
    log::info("client mode: the tactile model, rate and mapping are the server's (vtouching serve options)");
    return;
  }
  haptics::HapticConfig config = makeHapticConfig(options);  // throws before anything stops
  m_loop->stop();
  drain();
  m_options = options;
  m_config = std::move(config);
  if (m_recorder) m_recorder->config(options);
  startLoop();
}

void HapticSession::drain() {
  haptics::ContactTrace trace;
  while (m_traces.pop(trace)) {
    if (trace.contact >= m_contacts.size()) continue;
    ContactView& view = m_contacts[trace.contact];
    view.last = trace;
    std::int64_t& next = m_nextHistory_ns[trace.contact];
    if (trace.t_ns >= next) {
      view.history.erase(view.history.begin());
      view.history.push_back(trace.intensity);
      next = trace.t_ns + kHistoryStep_ns;
    }
    if (m_recorder) m_recorder->contact(trace);
  }
  haptics::ActuatorFrame frame;
  while (m_frames.pop(frame)) {
    m_lastFrame = frame;
    ++m_framesPlayed;
    if (m_recorder) m_recorder->frame(frame);
    if (m_actuatorRecorder) m_actuatorRecorder->record(frame);
    if (m_client) noteFrameLevels(frame);
  }
  updateRate(SteadyClock::instance().now_ns());
}

void HapticSession::noteFrameLevels(const haptics::ActuatorFrame& frame) {
  // Client mode has no contact traces (contacts are found on the server): show the levels.
  const std::int64_t now = SteadyClock::instance().now_ns();
  for (std::size_t a = 0; a < m_contacts.size(); ++a) {
    ContactView& view = m_contacts[a];
    view.last.contact = std::uint8_t(a);
    view.last.t_ns = frame.t_ns;
    view.last.intensity = a < frame.actuatorCount ? frame.intensity[a] : 0.0f;
    view.last.inContact = view.last.intensity > 0.0f;
    view.last.material = -1;
    if (now >= m_nextHistory_ns[a]) {
      view.history.erase(view.history.begin());
      view.history.push_back(view.last.intensity);
      m_nextHistory_ns[a] = now + kHistoryStep_ns;
    }
  }
}

void HapticSession::updateRate(std::int64_t now_ns) {
  if (now_ns - m_rateSince_ns < 1'000'000'000) return;
  const std::uint64_t ticks = m_loop ? m_loop->heartbeat() : m_framesPlayed;
  m_rate_hz = double(ticks - m_rateTicks) * 1e9 / double(now_ns - m_rateSince_ns);
  m_rateTicks = ticks;
  m_rateSince_ns = now_ns;
}

std::string HapticSession::networkStatus() const {
  if (!m_client) return "off (local haptic loop; vtouching serve / client for the network split)";
  const net::ClientStats s = m_client->stats();
  const net::Accept& session = m_client->session();
  std::string text = str("client of ", net::toString(m_server), ", session ", session.sessionId, ", codec ",
                         haptics::codecName(haptics::CodecId(session.codec)));
  if (!s.connected) {
    return text + (s.serverSaidBye ? ": the server ended the session" : ": the server went silent") +
           (m_reconnecting ? "; reconnecting (start the server again)" : "");
  }
  if (s.reconnects) text += str(" (resumed ", s.reconnects, "x)");
  char line[200];
  std::snprintf(line, sizeof line,
                "; rtt %.2f ms, playout delay %.1f ms, %llu played, %llu concealed, %llu lost, %llu late, buffer %u",
                double(s.rtt_ns) / 1e6, double(s.jitter.targetDelay_ns) / 1e6, (unsigned long long)s.jitter.played,
                (unsigned long long)s.jitter.concealed, (unsigned long long)s.jitter.lost,
                (unsigned long long)s.jitter.late, unsigned(s.jitter.depth));
  return text + line;
}

std::string HapticSession::gloveStatus() const {
  if (!m_driver) return "none";
  const auto s = m_driver->status();
  std::string text = str(m_simGlove ? "simulated " : "hid ", s.connected ? "connected " : "not connected ",
                         s.path, s.connected ? str(" ", int(s.sendRate_hz), " reports/s") : std::string());
  if (s.failsafe != haptics::FailsafeReason::None) text += str(" failsafe: ", haptics::failsafeReasonName(s.failsafe));
  if (!s.connected && !s.lastError.empty()) text += " (" + s.lastError + ")";
  return text;
}

std::array<float, haptics::kMaxActuators> HapticSession::gloveLevels() const {
  if (m_simGlove) return m_simGlove->levels();
  std::array<float, haptics::kMaxActuators> levels{};
  for (int a = 0; a < m_lastFrame.actuatorCount; ++a) levels[std::size_t(a)] = m_lastFrame.intensity[std::size_t(a)];
  return levels;
}

void HapticSession::stop() {
  if (m_stopped) return;
  m_stopped = true;
  if (m_loop) m_loop->stop();
  if (m_client) {
    m_forwarding.store(false);
    if (m_forwarder.joinable()) m_forwarder.join();
    m_client->disconnect();  // its last frame to the sinks is silent
  }
  drain();
  if (m_driver) m_driver->stop();
  if (m_actuatorRecorder) m_actuatorRecorder->finish();
  if (m_recorder) {
    m_recorder->finish();
    log::info("recorded ", m_recorder->frames(), " actuator frames to ", m_recorder->path().string(),
              droppedFrames() ? str(" (", droppedFrames(), " dropped: the replay will differ)") : std::string());
  }
}

}  // namespace vt::app
