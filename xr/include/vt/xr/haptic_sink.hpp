#pragma once
// Actuator frames from the haptic loop -> controller vibration, so a standard headset's
// controllers feel the vibration maps without a glove. Render thread only (OpenXR session thread).
#include "vt/haptics/actuator_frame.hpp"
#include "vt/xr/headset.hpp"

namespace vt::xr {

class XrHapticSink {
 public:
  /// Vibrates the controller of `hand` (0 left, 1 right); `headset` must outlive the sink.
  XrHapticSink(Headset& headset, int hand);
  /// amplitude = strongest actuator intensity, frequency = its frequency when nonzero, duration
  /// = one display period; a silent frame stops the vibration (once).
  void apply(const haptics::ActuatorFrame& frame);
  std::uint64_t pulses() const { return m_pulses; }

 private:
  Headset& m_headset;
  int m_hand;
  bool m_on = false;
  std::uint64_t m_pulses = 0;
};

}  // namespace vt::xr
