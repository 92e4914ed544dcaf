#pragma once
// A psychohaptic model of vibrotactile sensitivity: the detection threshold of the Pacinian
// channel (Verrillo's U-shaped curve), most sensitive near 250 Hz and rising by about
// 12 dB per octave on either side, flattening below 40 Hz where non-Pacinian channels take
// over. The perceptual codec spends its quantisation noise where the skin is least sensitive.
namespace vt::haptics {

/// Detection threshold in dB relative to the threshold at the most sensitive frequency (>= 0).
float vibrotactileThreshold_db(float frequency_hz) noexcept;
/// The most sensitive frequency of the model.
inline constexpr float kPeakSensitivity_hz = 250.0f;

}  // namespace vt::haptics
