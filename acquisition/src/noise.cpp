#include "vt/acquisition/noise.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>

namespace vt::acq {
namespace {

// E|s + n| for a constant s and n ~ N(0, sigma^2) (the folded normal's mean).
double foldedMean(double s, double sigma) noexcept {
  const double a = std::abs(s);
  if (sigma <= 0.0) return a;
  return sigma * std::sqrt(2.0 / std::numbers::pi) * std::exp(-a * a / (2 * sigma * sigma)) +
         a * std::erf(a / (sigma * std::numbers::sqrt2));
}

// sin of the quadrature phases over a quarter period (the sine's |value| distribution).
constexpr int kPhases = 16;
const std::array<double, kPhases>& quarterSine() {
  static const std::array<double, kPhases> table = [] {
    std::array<double, kPhases> t{};
    for (int i = 0; i < kPhases; ++i) t[std::size_t(i)] = std::sin((i + 0.5) / kPhases * std::numbers::pi / 2);
    return t;
  }();
  return table;
}

// E|s + n| for a zero-mean signal of RMS r whose kurtosis places it between three shapes of the
// same RMS: a square wave (kurtosis 1), a sine (1.5) and a Gaussian (3), mixed linearly in the
// kurtosis (the fourth moments of a mixture add). A texture crossed at constant speed is close to
// a sine; noise-like roughness is closer to a Gaussian.
double modelMeanAbs(double r, double kurtosis, double sigma) noexcept {
  const double k = std::clamp(kurtosis, 1.0, 3.0);
  double sine = 0.0;
  if (sigma > 0.0) {
    for (double s : quarterSine()) sine += foldedMean(r * std::numbers::sqrt2 * s, sigma);
    sine /= kPhases;
  } else {
    sine = 2 * std::numbers::sqrt2 / std::numbers::pi * r;  // mean |A sin| = 2 A / pi, A = sqrt(2) r
  }
  if (k <= 1.5) {
    const double w = (k - 1.0) / 0.5;
    return (1 - w) * foldedMean(r, sigma) + w * sine;
  }
  const double w = (k - 1.5) / 1.5;
  return (1 - w) * sine + w * std::sqrt(2.0 / std::numbers::pi) * std::sqrt(r * r + sigma * sigma);
}

}  // namespace

NoiseFloor estimateNoiseFloor(const std::vector<LineResult>& lines) noexcept {
  double sumSq = 0.0;
  std::size_t samples = 0, dof = 0;
  for (const LineResult& line : lines) {
    for (const PassFit& p : line.passes) {
      sumSq += p.restSumSq_g2;
      samples += p.restSamples;
      dof += p.restDof;
    }
  }
  NoiseFloor floor;
  floor.samples = samples;
  floor.known = samples >= kMinRestSamples && dof > 0;
  if (floor.known) floor.sigma_g = std::sqrt(sumSq / double(dof));
  return floor;
}

namespace {

// The corrected mean |s| of a set of sample moments (mean |x|, x^2, x^4 over `count` samples).
double correctedMeanAbs(double m1, double m2x, double m4x, int count, double sigma) noexcept {
  if (sigma <= 0.0 || count == 0) return m1;
  // Noise independent of the signal: E[x^2] = E[s^2] + sigma^2 and
  // E[x^4] = E[s^4] + 6 sigma^2 E[s^2] + 3 sigma^4 (odd moments of n vanish).
  const double s2 = sigma * sigma;
  const double m2 = std::max(0.0, m2x - s2);
  const double m4 = m4x - 6 * s2 * m2 - 3 * s2 * s2;
  const double kurtosis = m2 > 0.0 ? m4 / (m2 * m2) : 3.0;
  const double r = std::sqrt(m2);
  // Only the noise's excess is modelled; the measured mean |x| carries the signal's own shape,
  // so the result is exact without noise and as the signal grows large against it.
  const double excess = modelMeanAbs(r, kurtosis, sigma) - modelMeanAbs(r, kurtosis, 0.0);
  return std::max(0.0, m1 - excess);
}

}  // namespace

double noiseCorrectedValue(const Taxel& t, double sigma) noexcept {
  return correctedMeanAbs(t.v_g, t.m2_g2, t.m4_g4, t.samples, sigma);
}

TaxelStats noiseCorrectedStats(const std::vector<LineResult>& lines, double sigma_g) {
  std::vector<double> values;
  double noiseVariance = 0.0;  // mean variance of a taxel value from its own samples' noise
  for (const LineResult& line : lines) {
    for (const Taxel& t : line.taxels) {
      values.push_back(noiseCorrectedValue(t, sigma_g));
      // Split-half: each half's value has twice the full value's noise variance, so the full
      // value's is (a - b)^2 / 4 in expectation.
      const auto half = [&](const Taxel::Half& h) { return correctedMeanAbs(h.v_g, h.m2_g2, h.m4_g4, h.samples, sigma_g); };
      const double d = half(t.halves[0]) - half(t.halves[1]);
      noiseVariance += d * d / 4;
    }
  }
  TaxelStats s = computeStats(values);
  if (values.empty() || s.std <= 0.0) return s;
  noiseVariance /= double(values.size());
  // The spread of the values less their own noise; the extremes are pulled towards the mean by
  // the same factor (a shrinkage estimate: max - min of noisy values overshoots).
  const double spread = std::sqrt(std::max(0.0, s.std * s.std - noiseVariance));
  const double shrink = spread / s.std;
  s.min = s.mean + (s.min - s.mean) * shrink;
  s.max = s.mean + (s.max - s.mean) * shrink;
  s.scale = s.max - s.min;
  s.std = spread;
  return s;
}

}  // namespace vt::acq
