#pragma once
// The simulated glove behind the driver's tests: frames to submit and what the glove shows. The
// glove's keep-alive runs on a ManualClock that never moves, so any silence is the driver's doing.
#include <atomic>
#include <cstdint>

#include "vt/core/clock.hpp"
#include "vt/haptics/devices/glove_driver.hpp"
#include "vt/haptics/devices/sim_glove.hpp"
#include "vt/haptics/devices/sim_transport.hpp"

namespace vt::haptics::glove::test {

inline ActuatorFrame frameWith(float index, std::uint64_t sequence) {
  ActuatorFrame frame;
  frame.actuatorCount = kMaxActuators;
  frame.sequence = sequence;
  frame.intensity[std::size_t(ActuatorId::Index)] = index;
  return frame;
}

inline float indexLevel(const SimulatedGlove& glove) { return glove.levels()[std::size_t(ActuatorId::Index)]; }

inline bool allZero(const SimulatedGlove& glove) {
  for (float v : glove.levels()) {
    if (v != 0.0f) return false;
  }
  return true;
}

/// A simulated glove on its backend, and a heartbeat for the driver's watchdog.
struct SimRig {
  vt::ManualClock deviceClock{1'000'000'000};
  SimulatedGlove glove{deviceClock};
  SimGloveBackend backend{glove};
  std::atomic<std::uint64_t> beat{0};
  /// A driver config on this rig's heartbeat; the stall timeout is left at its default.
  GloveDriverConfig config() {
    GloveDriverConfig c;
    c.heartbeat = &beat;
    c.reconnectInterval_ns = 10'000'000;
    return c;
  }
};

}  // namespace vt::haptics::glove::test
