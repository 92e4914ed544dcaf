#pragma once
// Measurements on actuator waveforms, for benchmarks and tests of what a user would feel.
#include <span>

namespace vt::haptics {

/// |DFT|^2 of the waveform at one frequency. Any thread; allocation-free.
double spectralPower(std::span<const float> samples, double f_hz, double sampleRate_hz) noexcept;

/// The frequency (Hz, within [low_hz, high_hz]) where the waveform's spectrum peaks: a 0.5 Hz
/// DFT scan refined to 0.01 Hz around its best bin. Any thread; allocation-free.
double dominantFrequency_hz(std::span<const float> samples, double sampleRate_hz, double low_hz, double high_hz) noexcept;

}  // namespace vt::haptics
