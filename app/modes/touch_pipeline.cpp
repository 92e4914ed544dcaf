#include "modes/touch_pipeline.hpp"

#include <algorithm>
#include <cstdio>
#include <exception>

#include "ui/hud.hpp"
#include "vt/core/error.hpp"
#include "vt/core/log.hpp"
#include "vt/core/output_file.hpp"
#include "vt/core/realtime.hpp"
#include "vt/haptics/devices/recorder.hpp"

namespace vt::app {

namespace {
constexpr int kHapticThreadPriority = 20;
// The felt latency is handed to the loop again when it moves by more than this.
constexpr std::int64_t kLatencyStep_ns = 500'000;

// The network stream `serve` sends: the frame each pose-driven tick made goes to the server's
// encoder on its network thread; the client plays it a block and its playout delay later.
class StreamSink final : public haptics::ActuatorSink {
 public:
  StreamSink(SpscRing<haptics::ActuatorFrame>& ring, std::int64_t block_ns) : m_ring(ring), m_block_ns(block_ns) {}
  std::string name() const override { return "network stream"; }
  haptics::SinkThread thread() const override { return haptics::SinkThread::Realtime; }
  haptics::SinkPort port() override { return m_ring; }
  std::int64_t latency_ns() const override { return m_block_ns; }
  void stop() override {}  // the server, its only reader, stops first

 private:
  SpscRing<haptics::ActuatorFrame>& m_ring;
  std::int64_t m_block_ns;
};

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

TouchPipeline::TouchPipeline(const LoadedScene& scene, TouchPipelineSpec spec)
    : m_scene(scene), m_spec(std::move(spec)), m_options(m_spec.haptic), m_config(makeHapticConfig(m_options)) {
  const TouchDrive drive = m_spec.drive;
  if (drive == TouchDrive::Remote && !m_spec.remote) fail("touch pipeline: the remote drive needs a server (--connect)");
  if (drive == TouchDrive::Served && !m_spec.served) fail("touch pipeline: serving needs the server's settings");
  refuseSharedOutputs({{"--record", m_spec.sinks.record}, {"--record-csv", m_spec.sinks.actuatorCsv},
                       {"--record-wav", m_spec.sinks.actuatorWav}});
  // The outputs, every one of them here: a new output is one more line in this block.
  if (!m_spec.sinks.record.empty()) {
    m_recorder = static_cast<ReplayRecorder*>(
        &own(std::make_unique<ReplayRecorder>(m_spec.sinks.record, m_spec.sceneOptions, m_options)));
    // A client's frames are the server's: recorded for the meter, not replayable from the poses.
    if (drive == TouchDrive::Remote) m_recorder->remote(net::toString(m_spec.remote->server));
  }
  if (m_spec.sinks.glove != "none")
    m_glove = static_cast<haptics::glove::GloveSetup*>(&own(haptics::glove::GloveSetup::create(m_spec.sinks.glove)));
  if (!m_spec.sinks.outputs.outputs.empty()) {
    // Devices play in real time: stepped runs are not paced by the clock, and the server's output
    // plays on its client.
    if (drive == TouchDrive::Stepped || drive == TouchDrive::Served)
      fail("--output plays a live session (desktop, headset or client mode); not with this command");
    for (auto& sink : openOutputs(m_spec.sinks.outputs, m_config.actuatorCount())) own(std::move(sink));
  }
  if (drive == TouchDrive::Served) {
    // The codec block the server fills before it sends (4 ms unless the server fixes one).
    const int block_ms = m_spec.served->block_ms > 0 ? m_spec.served->block_ms : 4;
    own(std::make_unique<StreamSink>(m_streamFrames, std::int64_t(block_ms) * 1'000'000));
  }
  if (drive == TouchDrive::Remote) connect(*m_spec.remote);
  else startLoop();
  if (drive == TouchDrive::Served) serve(*m_spec.served);
  if (!m_spec.sinks.actuatorCsv.empty() || !m_spec.sinks.actuatorWav.empty()) {
    const int channels = m_client ? m_client->session().actuatorCount : m_config.actuatorCount();
    m_actuatorRecorder = &own(
        std::make_unique<haptics::ActuatorRecorder>(m_spec.sinks.actuatorCsv, m_spec.sinks.actuatorWav, channels));
  }
  updateFeltLatency();
}

TouchPipeline::~TouchPipeline() {
  // Destroyed by an error's unwinding: the listeners' owners may be gone already, and a run
  // stopped by an error leaves no recording (their destructors drop the temporaries).
  m_frameListeners.clear();
  m_traceListeners.clear();
  if (std::uncaught_exceptions() > 0) {
    std::erase_if(m_sinks, [this](const auto& sink) {
      return sink.get() == m_recorder || sink.get() == m_actuatorRecorder;
    });
    m_recorder = nullptr;
    m_actuatorRecorder = nullptr;
  }
  try {
    stop();
  } catch (const Error& e) {
    log::error(e.what());
  }
}

haptics::ActuatorSink& TouchPipeline::own(std::unique_ptr<haptics::ActuatorSink> sink) {
  m_sinks.push_back(std::move(sink));
  return *m_sinks.back();
}

haptics::ActuatorSink& TouchPipeline::attach(std::unique_ptr<haptics::ActuatorSink> sink) {
  // A realtime sink's port must be known to the frame source before it starts.
  if (sink->thread() != haptics::SinkThread::Main)
    fail("touch pipeline: ", sink->name(), " is a realtime output; those come from the pipeline's options");
  haptics::ActuatorSink& attached = own(std::move(sink));
  updateFeltLatency();
  return attached;
}

void TouchPipeline::startLoop() {
  haptics::HapticConfig config = m_config;
  // The live loop asks for SCHED_FIFO (granted to root / CAP_SYS_NICE): period jitter drops
  // from milliseconds to tens of microseconds on a busy machine (docs/PERFORMANCE.md).
  if (m_spec.drive == TouchDrive::LoopThread) config.realtimePriority = kHapticThreadPriority;
  config.outputLatency_ns = m_feltLatency_ns;
  m_loop = std::make_unique<haptics::HapticLoop>(config, *m_poses, *m_spec.clock);
  m_loop->setDisplayLag(m_displayLag_ns);
  m_loop->addOutput(m_frames);
  for (const auto& sink : m_sinks)
    if (sink->thread() == haptics::SinkThread::Realtime) m_loop->addOutput(sink->port());
  m_loop->setTraceOutput(m_traces);
  m_loop->publishScene(m_scene.haptic);
  m_meter.emplace(m_config.contacts, std::int64_t(1e9 / double(m_config.rate_hz)));
  m_meter->setFeltLatency(m_feltLatency_ns);
  resetViews(m_loop->config().contacts.size());
  if (m_spec.drive == TouchDrive::LoopThread) m_loop->start();
}

void TouchPipeline::serve(net::ServerConfig config) {
  // The network thread ticks the loop at each received pose's time and sends that tick's frame.
  config.poses = m_poses.get();
  config.tick = [this](std::int64_t t_ns, haptics::ActuatorFrame& frame) {
    m_loop->tickOnce(t_ns);
    while (m_streamFrames.pop(frame)) {
    }
  };
  config.actuatorCount = m_config.actuatorCount();
  config.blockLength = m_config.blockLength();
  config.sampleRate_hz = int(m_config.tactile.sampleRate_hz);
  m_server = std::make_unique<net::Server>(std::move(config));
  m_server->start();
}

void TouchPipeline::resetViews(std::size_t count) {
  m_contacts.assign(count, ContactView{});
  for (auto& c : m_contacts) c.history.assign(kHistory, 0.0f);
  m_nextHistory_ns.assign(count, 0);
  m_rateTicks = m_loop ? m_loop->heartbeat() : m_framesPlayed;
  m_ratePoses = m_poses->published();
  m_rateSince_ns = m_spec.clock->now_ns();
}

bool TouchPipeline::tick(std::int64_t t_ns, std::optional<std::int64_t> hand_t_ns) {
  if (m_spec.drive != TouchDrive::Stepped || !m_loop) return false;
  return hand_t_ns ? m_loop->tickOnce(t_ns, *hand_t_ns) : m_loop->tickOnce(t_ns);
}

void TouchPipeline::onFrame(std::function<void(const haptics::ActuatorFrame&)> listener) {
  m_frameListeners.push_back(std::move(listener));
}

void TouchPipeline::onTrace(std::function<void(const haptics::ContactTrace&)> listener) {
  m_traceListeners.push_back(std::move(listener));
}

void TouchPipeline::connect(net::ClientConfig config) {
  config.sceneDigest = tactileDigest(*m_scene.scene);
  config.sceneName = m_scene.description;
  // The network thread plays the stream out: it is this side's haptic thread.
  config.realtimePriority = kHapticThreadPriority;
  m_remoteServer = config.server;
  m_reconnecting = config.reconnect;
  config.outputs.add(m_frames);
  for (const auto& sink : m_sinks)
    if (sink->thread() == haptics::SinkThread::Realtime) config.outputs.add(sink->port());
  // net::Client's sender samples the history at the stream's block rate, each pose stamped
  // with the time it describes.
  config.poses = m_poses.get();
  config.sampling = m_config.sampling;
  m_client = std::make_unique<net::Client>(std::move(config));
  m_client->connect();
  m_meter.emplace(m_config.contacts, std::int64_t(1e9 / double(m_client->session().sampleRate_hz) *
                                                  double(m_client->session().blockLength)));
  m_meter->setFeltLatency(m_feltLatency_ns);
  // The HUD shows one line per actuator of the server's stream (named after this side's mapping).
  resetViews(std::min<std::size_t>(m_client->session().actuatorCount, m_config.contacts.size()));
}

void TouchPipeline::setOptions(const HapticOptions& options) {
  if (m_client || m_server) {
    log::info(m_client ? "client mode: the tactile model, rate and mapping are the server's (vtouching serve options)"
                       : "serve: the settings are fixed while a client may be connected");
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
  updateFeltLatency();
}

void TouchPipeline::updateFeltLatency() {
  std::int64_t latency = 0;
  for (const auto& sink : m_sinks)
    if (sink->felt()) latency = std::max(latency, sink->latency_ns());
  latency += std::int64_t(double(m_options.hapticLatency_ms) * 1e6);
  if (std::llabs(latency - m_feltLatency_ns) <= kLatencyStep_ns && m_feltLatency_ns != 0) return;
  m_feltLatency_ns = latency;
  if (m_loop) m_loop->setOutputLatency(latency);
  if (m_meter) m_meter->setFeltLatency(latency);
}

void TouchPipeline::setDisplayLag(std::int64_t lag_ns) {
  m_displayLag_ns = lag_ns;
  if (m_loop) m_loop->setDisplayLag(lag_ns);
}

std::int64_t TouchPipeline::feltDisplayLag_ns() const {
  if (m_loop) return m_loop->renderedDisplayLag_ns();
  // Client mode: a frame is felt the stream delay plus the felt latency after its pose was sent,
  // and plays the hand the lead in use past the send time.
  if (m_client && m_feltAfterSend_ns != 0) return m_feltAfterSend_ns - m_client->handLead_ns();
  return m_displayLag_ns;
}

void TouchPipeline::updateHandLead() {
  // Client mode: the hand sent now comes back as a frame felt a stream delay (measured: the
  // median of the recent ones) plus the felt outputs' latency later; the display shows it a lag
  // later. Sending the hand that far ahead (or behind) makes the two meet.
  const std::size_t n = std::min(m_streamDelayCount, m_streamDelays.size());
  if (!m_client || n == 0) return;
  auto sorted = m_streamDelays;
  std::nth_element(sorted.begin(), sorted.begin() + std::ptrdiff_t(n / 2), sorted.begin() + std::ptrdiff_t(n));
  m_feltAfterSend_ns = sorted[n / 2] + m_feltLatency_ns;
  m_client->setHandLead(m_feltAfterSend_ns - m_displayLag_ns);
}

void TouchPipeline::notePlayedFrame(const haptics::ActuatorFrame& frame) {
  // Client mode: contacts are found on the server, so the felt side is rebuilt here from what
  // was played: the hand this side sent for the frame (its time) against the same scene.
  if (frame.pose_t_ns == 0 || frame.hand_t_ns == 0) return;  // concealment or silence
  m_streamDelays[m_streamDelayCount++ % m_streamDelays.size()] = frame.t_ns - frame.pose_t_ns;
  if (!m_meter) return;
  const PoseSample sample = m_poses->sample(frame.hand_t_ns, m_config.sampling);
  if (!sample.pose.valid) return;
  const std::size_t count = m_config.contacts.size();
  std::array<collision::Sphere, haptics::kMaxContactPoints> spheres{};
  std::array<collision::SphereContact, haptics::kMaxContactPoints> contacts{};
  for (std::size_t c = 0; c < count; ++c) {
    const HandJoint joint = m_config.contacts[c].joint;
    const float radius = m_config.contacts[c].radius_m > 0.0f ? m_config.contacts[c].radius_m
                                                               : sample.pose.radius_m[std::size_t(joint)];
    spheres[c] = {sample.pose.at(joint), radius > 0.0f ? radius : kDefaultFingertipRadius_m};
  }
  m_scene.haptic->collision->sphereContacts({spheres.data(), count}, {contacts.data(), count});
  for (std::size_t c = 0; c < count; ++c) {
    haptics::ContactTrace trace;
    trace.t_ns = frame.t_ns;
    trace.tick = frame.sequence;
    trace.contact = std::uint8_t(c);
    trace.inContact = contacts[c].hit();
    trace.normal = contacts[c].hit() ? contacts[c].normal : glm::vec3(0.0f, 1.0f, 0.0f);
    trace.pose_t_ns = frame.hand_t_ns;
    trace.tip_m = spheres[c].center;
    if (m_recorder) m_recorder->contact(trace);
    m_meter->addTrace(trace);
  }
}

void TouchPipeline::drain() {
  readPoses();
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
    if (m_meter) m_meter->addTrace(trace);
    for (const auto& listener : m_traceListeners) listener(trace);
  }
  haptics::ActuatorFrame frame;
  while (m_frames.pop(frame)) {
    // A frame made after the first read may have seen a newer pose: the recording writes a
    // pose before the first frame that used it.
    if (frame.pose_t_ns > m_newestPoseRead_ns) readPoses();
    m_lastFrame = frame;
    ++m_framesPlayed;
    for (const auto& sink : m_sinks)
      if (sink->thread() == haptics::SinkThread::Main) sink->deliver(frame);
    if (m_client) {
      noteFrameLevels(frame);
      notePlayedFrame(frame);
    }
    for (const auto& listener : m_frameListeners) listener(frame);
  }
  for (const auto& sink : m_sinks)
    if (sink->thread() == haptics::SinkThread::Main) sink->flush();
  updateFeltLatency();
  updateHandLead();
  updateRates(m_spec.clock->now_ns());
}

void TouchPipeline::noteDrawnFrame(const HandPose& drawn, std::int64_t display_t_ns) {
  if (!drawn.valid) return;
  DrawnFrame frame;
  frame.display_t_ns = display_t_ns;
  frame.hand_t_ns = drawn.t_ns;
  for (std::size_t c = 0; c < m_config.contacts.size(); ++c) frame.tip_m[c] = drawn.at(m_config.contacts[c].joint);
  if (m_meter) m_meter->addFrame(frame);
  if (m_recorder) m_recorder->drawn(frame, m_config.contacts.size());
}

std::string TouchPipeline::timingStatus() const {
  HandPose newest;
  const bool have = m_poses->newest(newest);
  const double age_ms = have ? double(m_spec.clock->now_ns() - newest.t_ns) / 1e6 : 0.0;
  char line[240];
  std::snprintf(line, sizeof line, "poses %s, newest %s %.1f ms, %s; felt %.1f ms after its tick, display lag %.1f ms",
                ui::rateText(m_poseRate_hz).c_str(), age_ms < 0 ? "ahead" : "age", std::abs(age_ms),
                poseSamplingName(m_options.sampling), double(m_feltLatency_ns) / 1e6, double(m_displayLag_ns) / 1e6);
  return line;
}

std::string TouchPipeline::outputsStatus() const {
  std::string text;
  for (const auto& sink : m_sinks) {
    if (sink.get() == m_glove || !sink->felt()) continue;
    const std::string line = sink->statusLine();
    if (line.empty()) continue;
    if (!text.empty()) text += "; ";
    text += line;
  }
  return text;
}

void TouchPipeline::readPoses() {
  // Every pose the input wrote since the last drain, from whichever thread wrote it: the
  // recording replays them, the meter tells from them when the hand moves.
  const std::uint64_t published = m_poses->published();
  HandPose pose;
  std::uint32_t segment = 0;
  for (; m_posesRead < published; ++m_posesRead) {
    if (!m_poses->at(m_posesRead, pose, segment)) {
      ++m_posesMissed;  // overwritten before this drain: the replay will differ
      continue;
    }
    if (m_recorder) m_recorder->pose(pose, segment != m_poseSegment);
    if (m_meter) m_meter->addInput(pose);
    m_newestPoseRead_ns = pose.t_ns;
    m_poseSegment = segment;
  }
}

void TouchPipeline::noteFrameLevels(const haptics::ActuatorFrame& frame) {
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

void TouchPipeline::updateRates(std::int64_t now_ns) {
  if (now_ns - m_rateSince_ns < 1'000'000'000) return;
  const std::uint64_t ticks = m_loop ? m_loop->heartbeat() : m_framesPlayed;
  const std::uint64_t poses = m_poses->published();
  const double seconds = double(now_ns - m_rateSince_ns) * 1e-9;
  m_rate_hz = double(ticks - m_rateTicks) / seconds;
  m_poseRate_hz = double(poses - m_ratePoses) / seconds;
  m_rateTicks = ticks;
  m_ratePoses = poses;
  m_rateSince_ns = now_ns;
  if (m_meter) m_consistencyLine = m_meter->report().line();
}

std::string TouchPipeline::networkStatus() const {
  if (!m_client) return "off (local haptic loop; vtouching serve / client for the network split)";
  const net::ClientStats s = m_client->stats();
  const net::Accept& session = m_client->session();
  std::string text = str("client of ", net::toString(m_remoteServer), ", session ", session.sessionId, ", codec ",
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

std::array<float, haptics::kMaxActuators> TouchPipeline::gloveLevels() const {
  if (m_glove && m_glove->simulated()) return m_glove->simulated()->levels();
  std::array<float, haptics::kMaxActuators> levels{};
  for (int a = 0; a < m_lastFrame.actuatorCount; ++a) levels[std::size_t(a)] = m_lastFrame.intensity[std::size_t(a)];
  return levels;
}

void TouchPipeline::stop() {
  if (m_stopped) return;
  m_stopped = true;
  // The source first (its last frame to every sink is silent), then every sink.
  if (m_server) m_server->stop();
  if (m_loop) m_loop->stop();
  if (m_client) m_client->disconnect();
  drain();
  std::exception_ptr failure;
  for (const auto& sink : m_sinks) {
    try {
      sink->stop();
    } catch (...) {
      if (!failure) failure = std::current_exception();
    }
  }
  if (failure) std::rethrow_exception(failure);
  if (m_recorder) {
    log::info("recorded ", m_recorder->frames(), " actuator frames to ", m_recorder->path().string(),
              droppedRecords() ? str(" (", droppedRecords(), " dropped: the replay will differ)") : std::string());
  }
}

}  // namespace vt::app
