#include "vt/haptics/codec/spqi.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>

#include "dct.hpp"
#include "vt/core/error.hpp"

namespace vt::haptics {

namespace {

// The mapping of the normalised difference to a score (the paper's eta and threshold).
constexpr double kEta = 0.3;
constexpr double kOffset = -2.0;

// Per-bin weights 10^(-T_k / 10): dividing |X_k|^2 by them is "dB spectrum minus threshold".
std::vector<double> thresholdPower(int n, double sampleRate_hz) {
  std::vector<double> power = spqiThreshold_db(n, sampleRate_hz);
  for (double& p : power) p = std::pow(10.0, p / 10.0);
  return power;
}

}  // namespace

std::vector<double> spqiThreshold_db(int blockLength, double sampleRate_hz) {
  const double a = 1.0 - 250.0 / 550.0;
  const double la = std::log10(a);
  std::vector<double> t(std::size_t(std::max(blockLength, 0)));
  for (std::size_t k = 0; k < t.size(); ++k) {
    const double f = double(k) * sampleRate_hz / double(2 * blockLength - 1);
    const double l = std::log10(f / 550.0 + a);
    t[k] = std::fabs(62.0 / (la * la) * l * l) - 77.0;
  }
  // From the first positive value on the curve is flat (no positive value: flat from bin 0).
  const auto firstPositive = std::find_if(t.begin(), t.end(), [](double v) { return v > 0.0; });
  const double hold = firstPositive == t.end() ? (t.empty() ? 0.0 : t.front()) : *firstPositive;
  std::fill(firstPositive == t.end() ? t.begin() : firstPositive, t.end(), hold);
  return t;
}

double spqi(std::span<const float> reference, std::span<const float> distorted, double sampleRate_hz) {
  constexpr int n = kSpqiBlock;
  if (reference.size() < std::size_t(n))
    fail("spqi: the reference has ", reference.size(), " samples, fewer than one ", n, "-sample block");
  if (distorted.size() < reference.size())
    fail("spqi: the distorted signal has ", distorted.size(), " samples, fewer than the reference's ", reference.size());
  distorted = distorted.first(reference.size());
  if (std::equal(reference.begin(), reference.end(), distorted.begin())) return 1.0;

  const std::vector<double> weight = thresholdPower(n, sampleRate_hz);
  std::vector<float> table(std::size_t(codec::dctTableSize(n))), work(2 * std::size_t(n));
  std::vector<float> refX(n), distX(n);
  codec::makeDctTable(n, table);
  const std::size_t blocks = reference.size() / std::size_t(n);
  double sum = 0.0;
  for (std::size_t b = 0; b < blocks; ++b) {
    codec::dctForward(table, reference.subspan(b * n, n), refX, work);
    codec::dctForward(table, distorted.subspan(b * n, n), distX, work);
    double difference = 0.0, energy = 0.0;
    for (std::size_t k = 0; k < std::size_t(n); ++k) {
      const double r = double(refX[k]) * refX[k] / weight[k], d = double(distX[k]) * distX[k] / weight[k];
      difference += std::fabs(r - d);
      energy += r;
    }
    // No difference at all: D = -inf and the block scores 1 (tanh(-inf) = -1).
    if (difference == 0.0) {
      sum += 1.0;
      continue;
    }
    const double d_db = 10.0 * std::log10(difference / (energy + std::numeric_limits<double>::epsilon()));
    sum += (1.0 - std::tanh(kEta * d_db - kOffset)) / 2.0;
  }
  return sum / double(blocks);
}

}  // namespace vt::haptics
