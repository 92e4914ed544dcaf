#include "modes/touch_session.hpp"

#include <algorithm>
#include <cstdio>
#include <exception>

#include "ui/hud.hpp"
#include "vt/core/error.hpp"
#include "vt/core/log.hpp"
#include "vt/core/output_file.hpp"
#include "vt/core/realtime.hpp"

namespace vt::app {

namespace {
constexpr int kHapticThreadPriority = 20;
}  // namespace

HapticSinks readHapticSinks(cli::Args& args, const char* defaultGlove) {
  HapticSinks sinks;
  sinks.glove = args.valueOr("glove", defaultGlove);
  if (sinks.glove != "sim" && sinks.glove != "none" && sinks.glove != "hid" && sinks.glove.rfind("hid:", 0) != 0)
    fail(args.command(), ": --glove '", sinks.glove, "' is not sim|hid|hid:SERIAL|hid:/dev/hidrawN|none");
  sinks.record = args.valueOr("record", "");
  sinks.actuatorCsv = args.valueOr("record-csv", "");
  sinks.actuatorWav = args.valueOr("record-wav", "");
  sinks.outputs = readOutputSpecs(args);
  return sinks;
}

TouchSession::TouchSession(const LoadedScene& scene, TouchSessionSpec spec)
    : m_scene(scene), m_spec(std::move(spec)), m_options(m_spec.haptic), m_config(makeHapticConfig(m_options)) {
  const bool remote = m_spec.drive == TouchDrive::Remote;
  if (remote && !m_spec.remote) fail("touch session: the remote drive needs a server (--connect)");
  refuseSharedOutputs({{"--record", m_spec.sinks.record}, {"--record-csv", m_spec.sinks.actuatorCsv},
                       {"--record-wav", m_spec.sinks.actuatorWav}});
  // The sinks, every one of them here: a new output is one more line in this block.
  if (!m_spec.sinks.record.empty()) {
    // A replay re-runs the local loop; a remote server's output cannot be reproduced from poses.
    if (remote) fail("--record replays the local haptic loop; in client mode record with --record-csv/--record-wav");
    m_recorder.emplace(m_spec.sinks.record, m_spec.sceneOptions, m_options);
  }
  if (m_spec.sinks.glove != "none") m_glove = haptics::glove::GloveSetup::create(m_spec.sinks.glove);
  if (!m_spec.sinks.outputs.outputs.empty()) {
    // Devices play in real time: only the live loop feeds them (a remote stream reaches the glove
    // and the main thread only; stepped runs are not paced by the clock).
    if (m_spec.drive != TouchDrive::LoopThread)
      fail("--output plays the live haptic loop (desktop or headset mode); not with this command");
    m_outputs.emplace(m_spec.sinks.outputs, m_config.actuatorCount());
  }
  if (remote) connect(*m_spec.remote);
  else startLoop();
  if (!m_spec.sinks.actuatorCsv.empty() || !m_spec.sinks.actuatorWav.empty()) {
    const int channels = m_client ? m_client->session().actuatorCount : m_config.actuatorCount();
    m_actuatorRecorder.emplace(m_spec.sinks.actuatorCsv, m_spec.sinks.actuatorWav, channels);
  }
}

TouchSession::~TouchSession() {
  // Destroyed by an error's unwinding: the listeners' owners may be gone already, and a run
  // stopped by an error leaves no recording (their destructors drop the temporaries).
  m_frameListeners.clear();
  m_traceListeners.clear();
  if (std::uncaught_exceptions() > 0) {
    m_recorder.reset();
    m_actuatorRecorder.reset();
  }
  try {
    stop();
  } catch (const Error& e) {
    log::error(e.what());
  }
}

void TouchSession::startLoop() {
  haptics::HapticConfig config = m_config;
  // The live loop asks for SCHED_FIFO (granted to root / CAP_SYS_NICE): period jitter drops
  // from milliseconds to tens of microseconds on a busy machine (docs/PERFORMANCE.md).
  if (m_spec.drive == TouchDrive::LoopThread) config.realtimePriority = kHapticThreadPriority;
  m_loop = std::make_unique<haptics::HapticLoop>(config, *m_poses, *m_spec.clock);
  m_loop->addOutput(m_frames);
  if (m_glove) m_loop->addOutput(m_glove->driver().mailbox());
  if (m_outputs)
    for (SpscRing<haptics::ActuatorFrame>* queue : m_outputs->queues()) m_loop->addOutput(*queue);
  m_loop->setTraceOutput(m_traces);
  m_loop->publishScene(m_scene.haptic);
  resetViews(m_loop->config().contacts.size());
  if (m_spec.drive == TouchDrive::LoopThread) m_loop->start();
}

void TouchSession::resetViews(std::size_t count) {
  m_felt.assign(kTipWindow, TimedTip{});
  m_feltNext = 0;
  m_offsets_mm.assign(kTipWindow, 0.0f);
  m_offsetNext = 0;
  m_feltContact = 0;
  for (std::size_t c = 0; c < m_config.contacts.size(); ++c)
    if (m_config.contacts[c].joint == HandJoint::IndexTip) m_feltContact = c;
  m_contacts.assign(count, ContactView{});
  for (auto& c : m_contacts) c.history.assign(kHistory, 0.0f);
  m_nextHistory_ns.assign(count, 0);
  m_rateTicks = m_loop ? m_loop->heartbeat() : m_framesPlayed;
  m_ratePoses = m_poses->published();
  m_rateSince_ns = m_spec.clock->now_ns();
}

bool TouchSession::tick(std::int64_t t_ns) {
  return m_spec.drive == TouchDrive::Stepped && m_loop && m_loop->tickOnce(t_ns);
}

void TouchSession::onFrame(std::function<void(const haptics::ActuatorFrame&)> listener) {
  m_frameListeners.push_back(std::move(listener));
}

void TouchSession::onTrace(std::function<void(const haptics::ContactTrace&)> listener) {
  m_traceListeners.push_back(std::move(listener));
}

void TouchSession::connect(net::ClientConfig config) {
  config.sceneDigest = tactileDigest(*m_scene.scene);
  // The network thread plays the stream out: it is this side's haptic thread.
  config.realtimePriority = kHapticThreadPriority;
  m_server = config.server;
  m_reconnecting = config.reconnect;
  config.framesOut = &m_frames;
  config.latestOut = m_glove ? &m_glove->driver().mailbox() : nullptr;
  // net::Client's sender samples the history at the stream's block rate, each pose stamped
  // with the time it describes.
  config.poses = m_poses.get();
  config.sampling = m_config.sampling;
  m_client = std::make_unique<net::Client>(std::move(config));
  m_client->connect();
  // The HUD shows one line per actuator of the server's stream (named after this side's mapping).
  resetViews(std::min<std::size_t>(m_client->session().actuatorCount, m_config.contacts.size()));
}

void TouchSession::setOptions(const HapticOptions& options) {
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
  m_loop.reset();
  startLoop();
}

void TouchSession::drain() {
  recordPoses();
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
    for (const auto& listener : m_traceListeners) listener(trace);
    if (trace.contact == m_feltContact && trace.inContact) {
      m_felt[m_feltNext++ % kTipWindow] = {trace.pose_t_ns, trace.tip_m};
    }
  }
  matchDrawnHands();
  haptics::ActuatorFrame frame;
  while (m_frames.pop(frame)) {
    m_lastFrame = frame;
    ++m_framesPlayed;
    if (m_recorder) m_recorder->frame(frame);
    if (m_actuatorRecorder) m_actuatorRecorder->record(frame);
    if (m_client) noteFrameLevels(frame);
    for (const auto& listener : m_frameListeners) listener(frame);
  }
  updateRates(m_spec.clock->now_ns());
}

void TouchSession::noteDrawnHand(const HandPose& drawn) {
  if (m_drawn.size() >= kTipWindow) m_drawn.erase(m_drawn.begin());  // never matched: the hand is in the air
  m_drawn.push_back({drawn.t_ns, drawn.at(m_config.contacts[m_feltContact].joint)});
}

void TouchSession::matchDrawnHands() {
  // A drawn tip is compared once a haptic sample exists at or after its time (the headset draws
  // the hand at its display time, ahead of the ticks); the nearest sample in time is used.
  std::int64_t newest_ns = INT64_MIN;
  for (const TimedTip& f : m_felt) newest_ns = std::max(newest_ns, f.t_ns);
  std::erase_if(m_drawn, [&](const TimedTip& drawn) {
    if (drawn.t_ns > newest_ns) return false;
    const TimedTip* nearest = nullptr;
    for (const TimedTip& f : m_felt)
      if (f.t_ns != 0 && (!nearest || std::llabs(f.t_ns - drawn.t_ns) < std::llabs(nearest->t_ns - drawn.t_ns))) nearest = &f;
    // Within one tick period; else the finger was not in contact then.
    if (nearest && std::llabs(nearest->t_ns - drawn.t_ns) <= std::int64_t(1e9 / double(m_config.rate_hz)))
      m_offsets_mm[m_offsetNext++ % kTipWindow] = glm::length(nearest->tip_m - drawn.tip_m) * 1000.0f;
    return true;
  });
}

double TouchSession::drawnVersusFelt_mm_p50() const {
  std::vector<float> v(m_offsets_mm.begin(), m_offsets_mm.begin() + std::ptrdiff_t(std::min(m_offsetNext, kTipWindow)));
  if (v.empty()) return 0.0;
  std::nth_element(v.begin(), v.begin() + std::ptrdiff_t(v.size() / 2), v.end());
  return v[v.size() / 2];
}

double TouchSession::drawnVersusFelt_mm_max() const {
  const auto n = std::ptrdiff_t(std::min(m_offsetNext, kTipWindow));
  return n == 0 ? 0.0 : *std::max_element(m_offsets_mm.begin(), m_offsets_mm.begin() + n);
}

std::string TouchSession::timingStatus() const {
  HandPose newest;
  const bool have = m_poses->newest(newest);
  const double age_ms = have ? double(m_spec.clock->now_ns() - newest.t_ns) / 1e6 : 0.0;
  char line[200];
  std::snprintf(line, sizeof line, "poses %s, newest %s %.1f ms, %s; drawn vs felt tip %.2f mm (max %.2f)",
                ui::rateText(m_poseRate_hz).c_str(), age_ms < 0 ? "ahead" : "age", std::abs(age_ms), poseSamplingName(m_options.sampling),
                drawnVersusFelt_mm_p50(), drawnVersusFelt_mm_max());
  return line;
}

void TouchSession::recordPoses() {
  // Every pose the input wrote since the last drain, from whichever thread wrote it.
  if (!m_recorder) return;
  const std::uint64_t published = m_poses->published();
  HandPose pose;
  std::uint32_t segment = 0;
  for (; m_posesRecorded < published; ++m_posesRecorded) {
    if (!m_poses->at(m_posesRecorded, pose, segment)) {
      ++m_posesMissed;  // overwritten before this drain: the replay will differ
      continue;
    }
    m_recorder->pose(pose, segment != m_recordedSegment);
    m_recordedSegment = segment;
  }
}

void TouchSession::noteFrameLevels(const haptics::ActuatorFrame& frame) {
  // Client mode has no contact traces (contacts are found on the server): show the levels.
  const std::int64_t now = m_spec.clock->now_ns();
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

void TouchSession::updateRates(std::int64_t now_ns) {
  if (now_ns - m_rateSince_ns < 1'000'000'000) return;
  const std::uint64_t ticks = m_loop ? m_loop->heartbeat() : m_framesPlayed;
  const std::uint64_t poses = m_poses->published();
  const double seconds = double(now_ns - m_rateSince_ns) * 1e-9;
  m_rate_hz = double(ticks - m_rateTicks) / seconds;
  m_poseRate_hz = double(poses - m_ratePoses) / seconds;
  m_rateTicks = ticks;
  m_ratePoses = poses;
  m_rateSince_ns = now_ns;
}

std::string TouchSession::networkStatus() const {
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

std::string TouchSession::gloveStatus() const {
  if (!m_glove) return "none";
  const auto s = m_glove->driver().status();
  std::string text = str(m_glove->simulated() ? "simulated " : "hid ", s.connected ? "connected " : "not connected ",
                         s.path, s.connected ? str(" ", int(s.sendRate_hz), " reports/s") : std::string());
  if (s.failsafe != haptics::FailsafeReason::None) text += str(" failsafe: ", haptics::failsafeReasonName(s.failsafe));
  if (!s.connected && !s.lastError.empty()) text += " (" + s.lastError + ")";
  return text;
}

std::array<float, haptics::kMaxActuators> TouchSession::gloveLevels() const {
  if (m_glove && m_glove->simulated()) return m_glove->simulated()->levels();
  std::array<float, haptics::kMaxActuators> levels{};
  for (int a = 0; a < m_lastFrame.actuatorCount; ++a) levels[std::size_t(a)] = m_lastFrame.intensity[std::size_t(a)];
  return levels;
}

void TouchSession::stop() {
  if (m_stopped) return;
  m_stopped = true;
  if (m_loop) m_loop->stop();
  if (m_client) {
    m_client->disconnect();  // its last frame to the sinks is silent
  }
  drain();
  if (m_glove) m_glove->driver().stop();
  if (m_outputs) m_outputs->stop();
  if (m_actuatorRecorder) m_actuatorRecorder->finish();
  if (m_recorder) {
    m_recorder->finish();
    log::info("recorded ", m_recorder->frames(), " actuator frames to ", m_recorder->path().string(),
              droppedRecords() ? str(" (", droppedRecords(), " dropped: the replay will differ)") : std::string());
  }
}

}  // namespace vt::app
