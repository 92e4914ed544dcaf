#pragma once
// Accelerometer noise and the statistics corrected for it. White sensor noise n (std sigma) adds
// to the texture's signal s, and |s + n| averages above |s| (most where s is the size of the
// noise: smooth objects). sigma is measured where the stylus rests (before and after each pass);
// each taxel's mean |s| is then estimated from its moments. Pure functions, any thread.
#include <cstddef>
#include <vector>

#include "vt/acquisition/alignment.hpp"
#include "vt/acquisition/statistics.hpp"

namespace vt::acq {

/// The accelerometer's noise floor, from its readings while the robot stood still.
struct NoiseFloor {
  double sigma_g = 0.0;       // standard deviation of the reading at rest
  std::size_t samples = 0;    // rest readings used
  bool known = false;         // enough rest readings (kMinRestSamples)
};

/// Fewer rest readings than this over a scan leave the noise floor unknown (no correction).
inline constexpr std::size_t kMinRestSamples = 100;

/// The noise floor of the lines' rest readings (PassFit::restSamples, restSumSq_g2).
NoiseFloor estimateNoiseFloor(const std::vector<LineResult>& lines) noexcept;

/// A taxel's mean |s| with the noise's share removed: its mean |x| less the excess a signal of its
/// (noise-corrected) RMS and kurtosis would gain from noise of `sigma_g` (docs/scan-format.md,
/// "Sensor noise"). Equals v_g when sigma_g is 0; never below 0.
double noiseCorrectedValue(const Taxel& taxel, double sigma_g) noexcept;

/// Statistics of the lines' noise-corrected taxel values: V_mean their mean; V_std their spread
/// less the values' own noise variance (split-half: alternate samples of each taxel); min, max and
/// V_scale pulled towards the mean by the same factor.
TaxelStats noiseCorrectedStats(const std::vector<LineResult>& lines, double sigma_g);

}  // namespace vt::acq
