#include "vt/haptics/signal_analysis.hpp"

#include <complex>
#include <numbers>

namespace vt::haptics {
double spectralPower(std::span<const float> x, double f_hz, double sampleRate_hz) noexcept {
  std::complex<double> sum = 0.0, w = 1.0;
  const std::complex<double> step = std::polar(1.0, -2.0 * std::numbers::pi * f_hz / sampleRate_hz);
  for (float v : x) {
    sum += double(v) * w;
    w *= step;
  }
  return std::norm(sum);
}

double dominantFrequency_hz(std::span<const float> samples, double sampleRate_hz, double low_hz, double high_hz) noexcept {
  double best = low_hz, bestPower = -1.0;
  auto scan = [&](double from, double to, double step) {
    for (double f = from; f <= to; f += step) {
      if (const double p = spectralPower(samples, f, sampleRate_hz); p > bestPower) best = f, bestPower = p;
    }
  };
  scan(low_hz, high_hz, 0.5);
  scan(best - 0.5, best + 0.5, 0.01);
  return best;
}

}  // namespace vt::haptics
