#pragma once
// The normalised frequency scale shared by the haptic files (AHAP sharpness, .haptic frequency)
// and OpenXR parametric haptics: 0..1 spans kMinFrequency_hz..kMaxFrequency_hz linearly, and its
// middle, 0.5 (the default of .haptic and XR_EXT_haptic_parametric), is the nominal frequency,
// which is also what an unknown frequency (0 Hz, as the texture model records it) means. Any thread.
#include <algorithm>

namespace vt::haptics {

inline constexpr float kMinFrequency_hz = 50.0f;
inline constexpr float kMaxFrequency_hz = 450.0f;
/// The actuators' nominal carrier: where an unknown frequency plays, in every format and in play.
inline constexpr float kNominalFrequency_hz = 250.0f;

/// 0..1 across kMinFrequency_hz..kMaxFrequency_hz (clamped); unknown (<= 0 Hz) is 0.5.
inline float normaliseFrequency(float frequency_hz) noexcept {
  if (!(frequency_hz > 0.0f)) frequency_hz = kNominalFrequency_hz;
  return std::clamp((frequency_hz - kMinFrequency_hz) / (kMaxFrequency_hz - kMinFrequency_hz), 0.0f, 1.0f);
}
inline float frequencyFromNormalised(float normalised) noexcept {
  return kMinFrequency_hz + std::clamp(normalised, 0.0f, 1.0f) * (kMaxFrequency_hz - kMinFrequency_hz);
}

}  // namespace vt::haptics
