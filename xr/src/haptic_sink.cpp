#include "vt/xr/haptic_sink.hpp"

#include <algorithm>

namespace vt::xr {

XrHapticSink::XrHapticSink(Headset& headset, int hand) : m_headset(headset), m_hand(hand) {}

void XrHapticSink::apply(const haptics::ActuatorFrame& frame) {
  // One controller motor stands for all actuators: the strongest one drives it.
  int strongest = -1;
  float amplitude = 0.0f;
  for (int i = 0; i < frame.actuatorCount && i < haptics::kMaxActuators; ++i)
    if (frame.intensity[std::size_t(i)] > amplitude) {
      amplitude = frame.intensity[std::size_t(i)];
      strongest = i;
    }
  amplitude = std::clamp(amplitude, 0.0f, 1.0f);
  if (strongest < 0 || amplitude <= 0.0f) {
    if (m_on) m_headset.stopVibration(m_hand);
    m_on = false;
    return;
  }
  m_headset.vibrate(m_hand, amplitude, std::max(0.0f, frame.frequency_hz[std::size_t(strongest)]),
                    m_headset.displayPeriod_ns());
  m_on = true;
  ++m_pulses;
}

}  // namespace vt::xr
