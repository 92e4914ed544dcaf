#include "modes/haptic_session.hpp"

#include "vt/core/error.hpp"
#include "vt/core/log.hpp"
#include "vt/haptics/devices/sim_transport.hpp"

namespace vt::app {

GloveKind readGloveKind(cli::Args& args) {
  const std::string glove = args.valueOr("glove", "sim");
  if (glove == "sim") return GloveKind::Simulated;
  if (glove == "hid") return GloveKind::Hid;
  if (glove == "none") return GloveKind::None;
  fail(args.command(), ": --glove '", glove, "' is not sim|hid|none");
}

HapticSession::HapticSession(const LoadedScene& scene, const SceneOptions& sceneOptions, HapticOptions options,
                             GloveKind glove, const std::string& recordPath)
    : m_scene(scene), m_options(options) {
  if (!recordPath.empty()) m_recorder.emplace(recordPath, sceneOptions, options);
  if (glove == GloveKind::Simulated) {
    m_simGlove = std::make_unique<haptics::glove::SimulatedGlove>(SteadyClock::instance());
    m_backend = std::make_unique<haptics::glove::SimGloveBackend>(*m_simGlove);
  } else if (glove == GloveKind::Hid) {
    m_backend = haptics::glove::makeHidapiBackend();
  }
  if (m_backend) m_driver = std::make_unique<haptics::glove::GloveDriver>(*m_backend, haptics::glove::GloveDriverConfig{});
  startLoop();
}

HapticSession::~HapticSession() {
  try {
    stop();
  } catch (const Error& e) {
    log::error(e.what());
  }
}

namespace {
constexpr int kHapticThreadPriority = 20;
}  // namespace

void HapticSession::startLoop() {
  haptics::HapticConfig config = makeHapticConfig(m_options);
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
  makeHapticConfig(options);  // throws before anything stops
  m_loop->stop();
  drain();
  m_options = options;
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
    if (m_recorder) m_recorder->frame(frame);
  }
  const std::int64_t now = SteadyClock::instance().now_ns();
  if (now - m_rateSince_ns >= 1'000'000'000) {
    const std::uint64_t ticks = m_loop->heartbeat();
    m_rate_hz = double(ticks - m_rateTicks) * 1e9 / double(now - m_rateSince_ns);
    m_rateTicks = ticks;
    m_rateSince_ns = now;
  }
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
  m_loop->stop();
  drain();
  if (m_driver) m_driver->stop();
  if (m_recorder) {
    m_recorder->finish();
    log::info("recorded ", m_recorder->frames(), " actuator frames to ", m_recorder->path().string(),
              droppedFrames() ? str(" (", droppedFrames(), " dropped: the replay will differ)") : std::string());
  }
}

}  // namespace vt::app
