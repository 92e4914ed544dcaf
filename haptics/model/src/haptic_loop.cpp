#include "vt/haptics/haptic_loop.hpp"

#include <algorithm>
#include <cmath>

#include "vt/core/error.hpp"
#include "vt/core/realtime.hpp"
#include "vt/haptics/uv_lookup.hpp"

namespace vt::haptics {
namespace {

// The interpolation delay jumps up to a pose's age at once and relaxes over about this many ticks
// (slowly: each relaxation is then undone by a backward step of the sampled time).
constexpr std::int64_t kDelayDecayTicks = 65536;

double percentile_us(std::vector<std::uint32_t>& ns, double p) {
  if (ns.empty()) return 0.0;
  const auto k = std::size_t(std::min(double(ns.size() - 1), std::floor(p * double(ns.size()))));
  std::nth_element(ns.begin(), ns.begin() + std::ptrdiff_t(k), ns.end());
  return double(ns[k]) / 1000.0;
}

std::uint32_t clampNs(std::int64_t ns) noexcept {
  return std::uint32_t(std::clamp<std::int64_t>(ns, 0, 0xffffffffll));
}

}  // namespace

HapticLoop::HapticLoop(HapticConfig config, const PoseHistory& poses, const Clock& clock)
    : m_config(std::move(config)), m_poses(poses), m_clock(clock) {
  m_config.validate();
  m_blockLength = m_config.blockLength();
  m_outputLatency_ns.store(m_config.outputLatency_ns, std::memory_order_relaxed);
  for (auto& model : m_models) model = TactileModel(m_config.tactile);
}

HapticLoop::~HapticLoop() {
  stop();
  std::lock_guard lock(m_publishMutex);
  m_published.store(nullptr);
  m_retired.clear();
  m_current.reset();
}

void HapticLoop::addOutput(SinkPort port) {
  if (running()) fail("haptic loop: outputs must be added before start()");
  m_outputs.add(port);
}

void HapticLoop::setTraceOutput(SpscRing<ContactTrace>& ring) {
  if (running()) fail("haptic loop: the trace output must be set before start()");
  m_trace = &ring;
}

// Reclamation: the publisher stores the pointer, then bumps the epoch (release). A tick
// reads the epoch, then the pointer, and when done stores that epoch as its ack. A snapshot
// retired at epoch E is unreachable once ack >= E: the tick that acked E read a pointer at
// least as new as E's, and ticks run one after another. Frees happen here, never on the
// haptic thread.
void HapticLoop::publishScene(std::shared_ptr<const HapticScene> scene) {
  std::lock_guard lock(m_publishMutex);
  const std::uint64_t epoch = m_publishEpoch.load(std::memory_order_relaxed) + 1;
  m_published.store(scene.get(), std::memory_order_release);
  m_publishEpoch.store(epoch, std::memory_order_release);
  if (m_current) m_retired.emplace_back(std::move(m_current), epoch);
  m_current = std::move(scene);
  collectRetired();
}

void HapticLoop::collectRetired() {
  const std::uint64_t ack = m_ackEpoch.load(std::memory_order_acquire);
  std::erase_if(m_retired, [ack](const auto& entry) { return entry.second <= ack; });
}

void HapticLoop::reclaim() {
  std::lock_guard lock(m_publishMutex);
  collectRetired();
}

std::size_t HapticLoop::liveSnapshots() {
  std::lock_guard lock(m_publishMutex);
  return m_retired.size() + (m_current ? 1 : 0);
}

void HapticLoop::start() {
  if (m_running.exchange(true)) fail("haptic loop: already running");
  if (m_ticking.load()) {
    m_running = false;
    fail("haptic loop: start() while tickOnce() runs on another thread");
  }
  m_thread = std::thread([this] { run(); });
}

void HapticLoop::stop() noexcept {
  if (!m_thread.joinable()) return;
  m_running.store(false, std::memory_order_release);
  m_thread.join();
  std::lock_guard lock(m_publishMutex);
  collectRetired();
}

bool HapticLoop::tickOnce(std::int64_t t_ns) noexcept {
  if (running() || m_ticking.exchange(true)) return false;
  const std::int64_t start = m_clock.now_ns();
  tick(t_ns, nullptr);
  recordTick(m_clock.now_ns() - start);
  m_ticking.store(false);
  return true;
}

bool HapticLoop::tickOnce(std::int64_t t_ns, std::int64_t hand_t_ns) noexcept {
  if (running() || m_ticking.exchange(true)) return false;
  tick(t_ns, &hand_t_ns);
  m_heartbeat.fetch_add(1, std::memory_order_release);
  m_ticking.store(false);
  return true;
}

void HapticLoop::run() noexcept {
  // Best effort, once before the first tick; without permission the loop runs normally.
  if (m_config.realtimePriority > 0)
    m_realtime.store(requestRealtime("haptic", m_config.realtimePriority).granted(), std::memory_order_relaxed);
  const auto period = std::int64_t(std::llround(1e9 / double(m_config.rate_hz)));
  std::int64_t next = m_clock.now_ns() + period;
  std::int64_t last = -1;
  const bool spin = m_config.pacing == LoopPacing::Spin;
  while (m_running.load(std::memory_order_acquire)) {
    if (spin) {
      m_clock.spinUntil(next);
    } else {
      m_clock.sleepUntil(next);
    }
    const std::int64_t start = m_clock.now_ns();
    if (last >= 0) {
      const std::uint64_t j = m_jitterCount.load(std::memory_order_relaxed);
      m_jitterNs[j % kStatWindow].store(clampNs(std::llabs((start - last) - period)), std::memory_order_relaxed);
      m_jitterCount.store(j + 1, std::memory_order_release);
    }
    last = start;
    tick(start, nullptr);
    const std::int64_t end = m_clock.now_ns();
    recordTick(end - start);
    next += period;
    if (end >= next) {
      // Late by a whole period: skip the missed ticks instead of bursting to catch up.
      m_overruns.fetch_add(1, std::memory_order_relaxed);
      next += ((end - next) / period + 1) * period;
    }
  }
  emit(ActuatorFrame::silent(m_config.actuatorCount(), m_clock.now_ns()));
}

void HapticLoop::emit(const ActuatorFrame& frame) noexcept { m_outputs.emit(frame); }

void HapticLoop::recordTick(std::int64_t duration_ns) noexcept {
  const std::uint32_t ns = clampNs(duration_ns);
  const std::uint64_t n = m_heartbeat.load(std::memory_order_relaxed);
  m_tickNs[n % kStatWindow].store(ns, std::memory_order_relaxed);
  m_runTicks.add(ns);
  m_heartbeat.store(n + 1, std::memory_order_release);
}

void HapticLoop::tick(std::int64_t t_ns, const std::int64_t* hand_t_ns) noexcept {
  const std::uint64_t epoch = m_publishEpoch.load(std::memory_order_acquire);
  const HapticScene* world = m_published.load(std::memory_order_acquire);
  // The hand as it will be seen when this tick's output is felt (the tick's time plus the
  // output's latency, less the display's lag behind the hand), not the newest pose: poses arrive
  // at input or tracking rate, ticks at 1 kHz.
  // Interpolate mode looks back by the poses' recent age so that the time stays between two
  // poses: the price of never overshooting is that delay (docs/tactile-rendering.md, "Time").
  if (hand_t_ns) m_lead.set(t_ns, *hand_t_ns - t_ns);  // a replayed tick: exactly the recorded hand time
  // A changing lead is slewed in while something is touched; untouched, the hand's time may jump.
  const bool touching = std::any_of(m_contactState.begin(), m_contactState.end(), [](const ContactState& c) { return c.inContact; });
  const std::int64_t want_ns =
      t_ns + (hand_t_ns ? m_lead.lead_ns()
                        : m_lead.advance(t_ns,
                                         m_outputLatency_ns.load(std::memory_order_relaxed) -
                                             m_displayLag_ns.load(std::memory_order_relaxed),
                                         touching));
  const bool delayed = m_config.sampling.mode == PoseSampling::Interpolate;
  const PoseSample sample = m_poses.sample(delayed ? want_ns - m_interpolationDelay_ns : want_ns, m_config.sampling);
  if (sample.newest_t_ns != 0) {
    const std::int64_t age_ns = std::clamp<std::int64_t>(want_ns - sample.newest_t_ns, 0, m_config.sampling.timeout_ns);
    m_interpolationDelay_ns = age_ns >= m_interpolationDelay_ns
                                  ? age_ns
                                  : m_interpolationDelay_ns - (m_interpolationDelay_ns - age_ns) / kDelayDecayTicks;
  }
  const HandPose& pose = sample.pose;
  const bool havePose = pose.valid;
  if (!havePose) m_stalePoses.fetch_add(1, std::memory_order_relaxed);
  if (sample.extrapolated) m_predictedTicks.fetch_add(1, std::memory_order_relaxed);
  // Across a teleport (reset, re-centre, a jump) nothing is swept: contacts start afresh.
  const bool teleported = sample.segment != m_poseSegment;
  m_poseSegment = sample.segment;

  const std::size_t count = m_config.contacts.size();
  std::array<collision::Sphere, kMaxContactPoints> spheres{};
  std::array<collision::SphereContact, kMaxContactPoints> contacts{};
  if (havePose && world) {
    for (std::size_t i = 0; i < count; ++i) {
      const ContactPoint& cp = m_config.contacts[i];
      const float poseRadius = pose.radius_m[std::size_t(cp.joint)];
      spheres[i] = {pose.at(cp.joint), cp.radius_m > 0.0f ? cp.radius_m
                                                          : (poseRadius > 0.0f ? poseRadius : kDefaultFingertipRadius_m)};
    }
    world->collision->sphereContacts({spheres.data(), count}, {contacts.data(), count});
  }

  ActuatorFrame frame;
  frame.sequence = m_sequence++;
  frame.t_ns = t_ns;
  frame.pose_t_ns = sample.newest_t_ns;  // the newest pose the history held (replays rebuild it)
  frame.hand_t_ns = pose.t_ns;
  frame.actuatorCount = m_config.actuatorCount();
  frame.blockLength = std::uint16_t(m_blockLength);
  frame.sampleRate_hz = std::uint32_t(std::lround(m_config.tactile.sampleRate_hz));
  std::array<std::array<float, kMaxBlockSamples>, kMaxContactPoints> blocks;
  std::array<ContactOutput, kMaxContactPoints> outputs{};

  for (std::size_t i = 0; i < count; ++i) {
    const collision::SphereContact& c = contacts[i];
    ContactState& state = m_contactState[i];
    ContactInput in;
    ContactTrace trace;
    trace.t_ns = t_ns;
    trace.tick = frame.sequence;
    trace.contact = std::uint8_t(i);
    trace.pose_t_ns = pose.t_ns;
    trace.tip_m = spheres[i].center;
    if (c.hit()) {
      const Scene& scene = world->scene();
      const SceneObject& object = scene.objects[c.object];
      const Material& material = scene.materials[std::size_t(object.material)];
      const glm::vec2 uv = applyUvTransform(material.uvTransform,
                                            interpolateUv(scene.meshes[std::size_t(object.mesh)], c.triangle, c.u, c.v));
      in.inContact = true;
      in.map = material.vibrationMap >= 0 ? &(*world->maps)[std::size_t(material.vibrationMap)] : nullptr;
      in.mapAcross =
          material.vibrationMapAcross >= 0 && in.map ? &(*world->maps)[std::size_t(material.vibrationMapAcross)] : nullptr;
      in.scanDirectionUv = material.scanDirectionUv;
      in.wrap = material.wrapUv;
      in.uvEnd = uv;
      // Sweep from last tick's point only while sliding on the same object.
      in.uvStart = state.inContact && state.object == c.object && !teleported ? state.uv : uv;
      in.depth_m = c.depth_m;
      in.gain = material.tactileGain;
      state = {true, c.object, uv};
      trace.inContact = true;
      trace.object = c.object;
      trace.material = object.material;
      trace.u = uv.x;
      trace.v = uv.y;
      trace.normal = c.normal;
      trace.depth_m = c.depth_m;
    } else {
      state.inContact = false;
    }
    outputs[i] = m_models[i].render(in, {blocks[i].data(), std::size_t(m_blockLength)});
    trace.mapValue = in.inContact ? outputs[i].mapValue : 0.0f;
    trace.intensity = outputs[i].intensity;
    trace.acrossWeight = outputs[i].acrossWeight;
    if (m_trace) m_trace->push(trace);
  }

  for (const ActuatorRoute& route : m_config.routes) {
    const auto a = std::size_t(route.actuator);
    const ContactOutput& out = outputs[std::size_t(route.contact)];
    const float level = route.curve.apply(out.intensity * route.gain);
    // The waveform follows the level the curve produced (linear gain when the level is 0).
    const float scale = out.intensity > 0.0f ? level / out.intensity : route.gain;
    frame.intensity[a] = std::max(frame.intensity[a], level);
    if (out.frequency_hz > 0.0f) frame.frequency_hz[a] = out.frequency_hz;
    const auto& block = blocks[std::size_t(route.contact)];
    for (int k = 0; k < m_blockLength; ++k) {
      frame.block[a][std::size_t(k)] = std::clamp(frame.block[a][std::size_t(k)] + block[std::size_t(k)] * scale, -1.0f, 1.0f);
    }
  }
  emit(frame);
  m_ackEpoch.store(epoch, std::memory_order_release);
}

LoopStats HapticLoop::stats() const {
  LoopStats s;
  s.ticks = heartbeat();
  s.overruns = m_overruns.load(std::memory_order_relaxed);
  s.stalePoses = m_stalePoses.load(std::memory_order_relaxed);
  s.predictedTicks = m_predictedTicks.load(std::memory_order_relaxed);
  s.realtime = m_realtime.load(std::memory_order_relaxed);
  std::vector<std::uint32_t> ticks, jitter;
  const auto nTicks = std::size_t(std::min<std::uint64_t>(s.ticks, kStatWindow));
  const auto nJitter = std::size_t(std::min<std::uint64_t>(m_jitterCount.load(std::memory_order_acquire), kStatWindow));
  for (std::size_t i = 0; i < nTicks; ++i) ticks.push_back(m_tickNs[i].load(std::memory_order_relaxed));
  for (std::size_t i = 0; i < nJitter; ++i) jitter.push_back(m_jitterNs[i].load(std::memory_order_relaxed));
  if (!ticks.empty()) s.tickMax_us = double(*std::max_element(ticks.begin(), ticks.end())) / 1000.0;
  s.tickP50_us = percentile_us(ticks, 0.5);
  s.tickP99_us = percentile_us(ticks, 0.99);
  s.jitterP50_us = percentile_us(jitter, 0.5);
  s.jitterP99_us = percentile_us(jitter, 0.99);
  s.runTickP50_us = m_runTicks.percentile_us(0.5);
  s.runTickP99_us = m_runTicks.percentile_us(0.99);
  s.runTickMax_us = m_runTicks.max_us();
  return s;
}

}  // namespace vt::haptics
