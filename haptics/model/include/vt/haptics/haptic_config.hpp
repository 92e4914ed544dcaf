#pragma once
// Haptic loop configuration: rate, tactile model, contact points on the hand and how each
// contact point drives glove actuators. Plain data, set up before the loop starts.
#include <cstdint>
#include <vector>

#include "vt/haptics/actuator_frame.hpp"
#include "vt/haptics/tactile_model.hpp"
#include "vt/scene/hand.hpp"
#include "vt/scene/pose_history.hpp"

namespace vt::haptics {

/// Contact points the loop can track (fixed arrays on the haptic thread).
inline constexpr int kMaxContactPoints = 16;

/// A sphere on the hand that can touch things.
struct ContactPoint {
  HandJoint joint = HandJoint::IndexTip;
  float radius_m = 0.0f;  // 0 = the pose's joint radius (8 mm when the pose has none)
};

/// Maps a 0..1 level to a drive level: 0 stays 0, otherwise floor + (1 - floor) * level^gamma
/// (floor overcomes an actuator's dead zone; gamma shapes perceived loudness).
struct ResponseCurve {
  float gamma = 1.0f;
  float floor = 0.0f;

  float apply(float level) const noexcept;
};

/// One contact point driving one actuator.
struct ActuatorRoute {
  int contact = 0;  // index into HapticConfig::contacts
  ActuatorId actuator = ActuatorId::Index;
  float gain = 1.0f;
  ResponseCurve curve;
};

/// How the loop thread waits for its next tick.
enum class LoopPacing : std::uint8_t {
  /// Sleeps, then spins the last stretch (SteadyClock::sleepUntil): the core is free between ticks.
  Sleep,
  /// Busy-waits the whole period: the core never idles, so a tick never starts on a core that
  /// was halted (cold caches, a guest's vCPU descheduled). Takes a whole core; for machines with
  /// one to spare (docs/PERFORMANCE.md, "Pacing the haptic thread").
  Spin,
};

/// "sleep" / "spin", and back (false for any other text).
const char* loopPacingName(LoopPacing pacing) noexcept;
bool parseLoopPacing(const char* text, LoopPacing& out) noexcept;

/// Everything the loop needs to know before it starts. Setup threads.
struct HapticConfig {
  float rate_hz = 1000.0f;          // tick rate, 250..4000 Hz
  TactileModelConfig tactile;          // model, output sample rate (rate must divide it), ramps
  /// How each tick turns the pose history into the hand at its time (mode, timeout, horizon).
  PoseSamplingConfig sampling;
  /// The output path's delay (glove, audio buffer): each tick samples the hand this much later
  /// than its own time, so the vibration is felt when the hand is there.
  std::int64_t outputLatency_ns = 0;
  /// > 0: run the loop thread SCHED_FIFO at this priority (1..99) when the OS allows it
  /// (root or CAP_SYS_NICE / RLIMIT_RTPRIO); keeps period jitter low on a busy machine.
  int realtimePriority = 0;
  LoopPacing pacing = LoopPacing::Sleep;
  std::vector<ContactPoint> contacts;
  std::vector<ActuatorRoute> routes;

  /// Five fingertips driving the five fingertip actuators (the default).
  static HapticConfig fiveFingertips();
  /// The paper's V-Touching glove: index, middle and ring fingertips only.
  static HapticConfig vTouching();
  /// Throws vt::Error naming the field when something is out of range. Setup threads.
  void validate() const;
  /// Waveform samples per tick (sampleRate / rate).
  int blockLength() const noexcept;
  /// Actuators in use: highest routed id + 1.
  std::uint8_t actuatorCount() const noexcept;
};

}  // namespace vt::haptics
