#pragma once
// Sends the haptic loop's output as OSC messages over UDP (liblo), so a lab's own device, a
// microcontroller or a Max/Pd/SuperCollider patch can listen. Address space (docs/outputs.md):
//   /vtouching/levels       f...        intensity 0..1 of actuators 0..N-1
//   /vtouching/frequencies  f...        dominant frequency in Hz (0 = unknown)
//   /vtouching/actuator/<name> f f      intensity, frequency of one actuator ("index", ...)
//   /vtouching/block/<name> i f...      sample rate, then one tick's waveform (-1..1), if enabled
// Levels go out at `levelRate_hz` (the newest frame), blocks for every frame. A writer thread
// consumes the loop's frames from an SpscRing; the haptic thread never waits for the network.
// Every exit path (stop, SIGINT/SIGTERM, a stalled loop) sends zero levels.
#include <atomic>
#include <cstdint>
#include <memory>
#include <string>
#include <string_view>

#include "vt/haptics/devices/queued_output.hpp"

namespace vt::haptics {

struct OscOutputConfig {
  std::string host = "127.0.0.1";
  std::string port = "9000";
  int levelRate_hz = 250;  // levels messages per second (blocks follow every frame)
  bool blocks = false;     // also send each frame's waveform block
  FailsafeConfig failsafe;
  /// The haptic loop's tick counter (must outlive the output); nullptr: queued frames are the heartbeat.
  const std::atomic<std::uint64_t>* heartbeat = nullptr;
};

/// Parses "osc://HOST:PORT" (an optional "?blocks" asks for waveform blocks) into `config`.
/// Throws vt::Error naming the URL and the part that is wrong. Any thread.
OscOutputConfig parseOscUrl(std::string_view url, OscOutputConfig config = {});

/// A snapshot for the HUD and --json.
struct OscOutputStatus {
  std::string target;                // "osc://host:port"
  std::uint64_t messagesSent = 0;
  std::uint64_t sendErrors = 0;
  std::uint64_t queueDropped = 0;    // actuator frames refused by a full queue
  FailsafeReason failsafe = FailsafeReason::None;
  std::string lastError;
};

class OscOutput final : public QueuedOutput {
 public:
  /// Resolves the target (throws vt::Error naming it) and starts the writer thread. Main thread.
  explicit OscOutput(OscOutputConfig config, const Clock& clock = SteadyClock::instance());
  /// Same as stop(): sends zero levels first.
  ~OscOutput() override;

  /// Any non-real-time thread.
  OscOutputStatus status() const;
  /// ActuatorSink: felt after one levels period.
  std::string name() const override;
  std::int64_t latency_ns() const override;
  std::string statusLine() const override;

 private:
  struct Target;
  void writerLoop() noexcept override;
  void sendLevels(const ActuatorFrame& frame) noexcept;
  void sendBlock(const ActuatorFrame& frame) noexcept;
  void count(int result) noexcept;

  const OscOutputConfig m_config;
  std::unique_ptr<Target> m_target;
  std::atomic<std::uint64_t> m_sent{0}, m_errors{0};
};

}  // namespace vt::haptics
