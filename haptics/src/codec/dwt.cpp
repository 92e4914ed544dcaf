#include "dwt.hpp"

#include <algorithm>
#include <array>

#include "vt/haptics/actuator_frame.hpp"

namespace vt::haptics::codec {

namespace {

constexpr float kAlpha = -1.586134342f;
constexpr float kBeta = -0.05298011854f;
constexpr float kGamma = 0.8829110762f;
constexpr float kDelta = 0.4435068522f;
// Scales that make the transform close to orthonormal, so coefficient quantisation noise
// maps to the same noise energy in the signal (the step sizes then mean what they say).
constexpr float kLowScale = 1.41421356f / 1.230174105f;
constexpr float kHighScale = 1.230174105f / 1.41421356f;

using Buffer = std::array<float, kMaxBlockSamples>;

// s: even samples (ns), d: odd samples (nd); neighbour indices clamp = symmetric extension.
void lift(float* s, int ns, float* d, int nd, float a, float b) noexcept {
  for (int i = 0; i < nd; ++i) d[i] += a * (s[i] + s[std::min(i + 1, ns - 1)]);
  for (int i = 0; i < ns; ++i) s[i] += b * (d[std::clamp(i - 1, 0, nd - 1)] + d[std::min(i, nd - 1)]);
}
void unlift(float* s, int ns, float* d, int nd, float a, float b) noexcept {
  for (int i = 0; i < ns; ++i) s[i] -= b * (d[std::clamp(i - 1, 0, nd - 1)] + d[std::min(i, nd - 1)]);
  for (int i = 0; i < nd; ++i) d[i] -= a * (s[i] + s[std::min(i + 1, ns - 1)]);
}

void forwardLevel(float* x, int n) noexcept {
  Buffer s{}, d{};
  const int ns = (n + 1) / 2, nd = n / 2;
  for (int i = 0; i < ns; ++i) s[std::size_t(i)] = x[2 * i];
  for (int i = 0; i < nd; ++i) d[std::size_t(i)] = x[2 * i + 1];
  lift(s.data(), ns, d.data(), nd, kAlpha, kBeta);
  lift(s.data(), ns, d.data(), nd, kGamma, kDelta);
  for (int i = 0; i < ns; ++i) x[i] = s[std::size_t(i)] * kLowScale;
  for (int i = 0; i < nd; ++i) x[ns + i] = d[std::size_t(i)] * kHighScale;
}

void inverseLevel(float* x, int n) noexcept {
  Buffer s{}, d{};
  const int ns = (n + 1) / 2, nd = n / 2;
  for (int i = 0; i < ns; ++i) s[std::size_t(i)] = x[i] / kLowScale;
  for (int i = 0; i < nd; ++i) d[std::size_t(i)] = x[ns + i] / kHighScale;
  unlift(s.data(), ns, d.data(), nd, kGamma, kDelta);
  unlift(s.data(), ns, d.data(), nd, kAlpha, kBeta);
  for (int i = 0; i < ns; ++i) x[2 * i] = s[std::size_t(i)];
  for (int i = 0; i < nd; ++i) x[2 * i + 1] = d[std::size_t(i)];
}

}  // namespace

int dwtLevels(int n) noexcept {
  int levels = 0;
  while (levels < kMaxDwtLevels && (n + 1) / 2 >= 1 && n >= 2) {
    n = (n + 1) / 2;
    ++levels;
  }
  return levels;
}

void dwtBand(int n, int levels, int band, int& start, int& size) noexcept {
  // Lengths of the approximation after each level.
  std::array<int, kMaxDwtLevels + 1> len{};
  len[0] = n;
  for (int l = 1; l <= levels; ++l) len[std::size_t(l)] = (len[std::size_t(l - 1)] + 1) / 2;
  if (band == 0) {
    start = 0;
    size = len[std::size_t(levels)];
    return;
  }
  const int level = levels + 1 - band;  // band 1 = coarsest detail
  start = len[std::size_t(level)];
  size = len[std::size_t(level - 1)] - len[std::size_t(level)];
}

void dwtForward(std::span<float> x, int levels) noexcept {
  int n = int(x.size());
  for (int l = 0; l < levels && n >= 2; ++l) {
    forwardLevel(x.data(), n);
    n = (n + 1) / 2;
  }
}

void dwtInverse(std::span<float> x, int levels) noexcept {
  std::array<int, kMaxDwtLevels + 1> len{};
  len[0] = int(x.size());
  for (int l = 1; l <= levels; ++l) len[std::size_t(l)] = (len[std::size_t(l - 1)] + 1) / 2;
  for (int l = levels; l >= 1; --l)
    if (len[std::size_t(l - 1)] >= 2) inverseLevel(x.data(), len[std::size_t(l - 1)]);
}

}  // namespace vt::haptics::codec
