#pragma once
// The haptic loop: a fixed-rate thread (1 kHz default, up to 4 kHz) that samples the hand
// from the pose history at each tick's own time (interpolated between the poses that bracket
// it, predicted a bounded time past the newest), finds fingertip contacts in the published scene snapshot, renders them and
// writes one ActuatorFrame per tick to every registered output. The haptic thread never
// locks, allocates, logs or throws; everything it shares is lock-free.
#include <array>
#include <atomic>
#include <cstdint>
#include <memory>
#include <mutex>
#include <thread>
#include <vector>

#include "vt/core/clock.hpp"
#include "vt/core/latest_value.hpp"
#include "vt/scene/pose_history.hpp"
#include "vt/core/spsc_ring.hpp"
#include "vt/core/time_alignment.hpp"
#include "vt/haptics/actuator_frame.hpp"
#include "vt/haptics/actuator_sink.hpp"
#include "vt/haptics/haptic_config.hpp"
#include "vt/haptics/haptic_scene.hpp"
#include "vt/haptics/tick_histogram.hpp"
#include "vt/scene/hand.hpp"

namespace vt::haptics {

/// One contact point's state in one tick, for UI plots and CSV traces.
struct ContactTrace {
  std::int64_t t_ns = 0;
  std::uint64_t tick = 0;
  std::uint8_t contact = 0;   // index into HapticConfig::contacts
  bool inContact = false;
  std::uint32_t object = 0xffffffffu;  // scene object, or all ones
  std::int32_t material = -1;
  float u = 0.0f, v = 0.0f;   // map UV (after the material's uvTransform)
  glm::vec3 normal{0.0f, 1.0f, 0.0f};  // the touched triangle's outer normal, world space
  float depth_m = 0.0f;
  float mapValue = 0.0f;
  float intensity = 0.0f;     // the tactile model's level before routing
  std::int64_t pose_t_ns = 0;       // the time the hand was sampled for (tick + output latency)
  glm::vec3 tip_m{0.0f};            // the contact sphere's centre at that time (world)
  float acrossWeight = 0.0f;  // share of the across-scanned map (0: along / single map, 1: across)
};

/// Timing of the loop's recent ticks (the last kStatWindow), for HUDs and watchdogs, and of
/// every tick since the loop was made (1 us resolution), for run reports and benchmarks.
struct LoopStats {
  std::uint64_t ticks = 0;
  std::uint64_t overruns = 0;      // ticks that started a full period late
  std::uint64_t stalePoses = 0;    // ticks without a hand: no pose within the sampling timeout
  std::uint64_t predictedTicks = 0;  // ticks whose time lay past the newest pose (extrapolated or held)
  bool realtime = false;           // the thread got real-time priority (SCHED_FIFO or RealtimeKit)
  double tickP50_us = 0.0, tickP99_us = 0.0, tickMax_us = 0.0;
  double jitterP50_us = 0.0, jitterP99_us = 0.0;  // |actual period - nominal period|
  double runTickP50_us = 0.0, runTickP99_us = 0.0, runTickMax_us = 0.0;  // every tick (TickHistogram)
};

/// The fixed-rate haptic loop (thread rules per member below).
class HapticLoop {
 public:
  /// Ticks kept for statistics.
  static constexpr int kStatWindow = 4096;

  /// Validates `config` (throws vt::Error). `poses` and `clock` must outlive the loop.
  HapticLoop(HapticConfig config, const PoseHistory& poses, const Clock& clock = SteadyClock::instance());
  /// Stops the thread (actuators get a silent frame) and frees every snapshot.
  ~HapticLoop();
  HapticLoop(const HapticLoop&) = delete;
  HapticLoop& operator=(const HapticLoop&) = delete;

  /// Registers a realtime sink's port before start(); the loop is its only producer. Setup thread.
  void addOutput(SinkPort port);
  /// Per-tick, per-contact trace records (dropped and counted when the ring is full).
  void setTraceOutput(SpscRing<ContactTrace>& ring);

  /// Publishes a new immutable scene (nullptr = nothing to touch). Any non-haptic thread;
  /// old snapshots are freed here, on the publisher, once the haptic thread has moved on.
  void publishScene(std::shared_ptr<const HapticScene> scene);

  /// Frees retired snapshots the haptic thread has moved past (publishScene also does). Any
  /// non-haptic thread.
  void reclaim();
  /// Snapshots published but not yet freed (the current one included). Any non-haptic thread.
  std::size_t liveSnapshots();

  /// Starts the haptic thread. Setup thread.
  void start();
  /// Stops and joins it; the thread's last act is a silent frame to every output.
  void stop() noexcept;
  bool running() const noexcept { return m_running.load(std::memory_order_acquire); }

  /// One tick at time t_ns on the calling thread, for offscreen runs, replays and tests
  /// (deterministic). Refused (false) while the thread runs: outputs have one producer.
  bool tickOnce(std::int64_t t_ns) noexcept;
  /// The same, rendering the hand at exactly hand_t_ns (a replay reproducing a recorded tick).
  bool tickOnce(std::int64_t t_ns, std::int64_t hand_t_ns) noexcept;

  /// Ticks completed so far; a watchdog sees a stall when it stops growing. Any thread.
  std::uint64_t heartbeat() const noexcept { return m_heartbeat.load(std::memory_order_acquire); }
  /// Percentiles over recent ticks. Any non-haptic thread (it allocates).
  LoopStats stats() const;
  /// The validated configuration (immutable). Any thread.
  const HapticConfig& config() const noexcept { return m_config; }
  /// Each tick renders the hand as it will be seen when its output is felt: at tick +
  /// outputLatency - displayLag, where outputLatency is the felt outputs' delay (starts at
  /// config().outputLatency_ns) and displayLag how old the hand the display shows is when it is
  /// shown (vt/core/time_alignment.hpp: a change is slewed in, so the hand's time never stands
  /// still or jumps). Any thread.
  void setOutputLatency(std::int64_t latency_ns) noexcept { m_outputLatency_ns.store(latency_ns, std::memory_order_relaxed); }
  void setDisplayLag(std::int64_t lag_ns) noexcept { m_displayLag_ns.store(lag_ns, std::memory_order_relaxed); }
  std::int64_t outputLatency_ns() const noexcept { return m_outputLatency_ns.load(std::memory_order_relaxed); }
  std::int64_t displayLag_ns() const noexcept { return m_displayLag_ns.load(std::memory_order_relaxed); }
  /// The display lag the ticks render for now: displayLag while a change is slewed in. Any thread.
  std::int64_t renderedDisplayLag_ns() const noexcept { return outputLatency_ns() - m_lead.lead_ns(); }

 private:
  struct ContactState {
    bool inContact = false;
    std::uint32_t object = 0;
    glm::vec2 uv{0.0f};
  };

  void run() noexcept;
  void tick(std::int64_t t_ns, const std::int64_t* hand_t_ns) noexcept;
  void emit(const ActuatorFrame& frame) noexcept;
  void recordTick(std::int64_t duration_ns) noexcept;
  void collectRetired();

  HapticConfig m_config;
  const PoseHistory& m_poses;
  const Clock& m_clock;
  int m_blockLength = 0;

  FrameFanout m_outputs;
  SpscRing<ContactTrace>* m_trace = nullptr;
  std::atomic<std::int64_t> m_outputLatency_ns{0};
  std::atomic<std::int64_t> m_displayLag_ns{0};

  // Haptic-thread state.
  std::array<TactileModel, kMaxContactPoints> m_models;
  std::array<ContactState, kMaxContactPoints> m_contactState{};
  std::uint32_t m_poseSegment = 0;  // the pose history's segment of the last tick (teleports)
  std::int64_t m_interpolationDelay_ns = 0;  // Interpolate mode: the newest pose's recent age
  LeadSlew m_lead;                           // hand time - tick time
  std::uint64_t m_sequence = 0;

  // Snapshot publication: pointer + epoch written by the publisher, the epoch the haptic
  // thread last finished a tick with read back by it (see publishScene).
  std::atomic<const HapticScene*> m_published{nullptr};
  std::atomic<std::uint64_t> m_publishEpoch{0};
  std::atomic<std::uint64_t> m_ackEpoch{0};
  std::mutex m_publishMutex;  // serialises publishers only; the haptic thread never takes it
  std::shared_ptr<const HapticScene> m_current;
  std::vector<std::pair<std::shared_ptr<const HapticScene>, std::uint64_t>> m_retired;

  // Statistics, written by whichever thread ticks.
  std::atomic<std::uint64_t> m_heartbeat{0};
  std::atomic<std::uint64_t> m_overruns{0};
  std::atomic<std::uint64_t> m_stalePoses{0};
  std::atomic<std::uint64_t> m_predictedTicks{0};
  std::array<std::atomic<std::uint32_t>, kStatWindow> m_tickNs{};
  TickHistogram m_runTicks;
  std::array<std::atomic<std::uint32_t>, kStatWindow> m_jitterNs{};
  std::atomic<std::uint64_t> m_jitterCount{0};

  std::atomic<bool> m_realtime{false};
  std::atomic<bool> m_running{false};
  std::atomic<bool> m_ticking{false};  // a tickOnce is in progress (refuses start())
  std::thread m_thread;
};

}  // namespace vt::haptics
