#include "dct.hpp"

#include <cmath>
#include <numbers>

namespace vt::haptics::codec {

void makeDctTable(int n, std::span<float> table) noexcept {
  for (int m = 0; m < 4 * n; ++m)
    table[std::size_t(m)] = float(std::cos(std::numbers::pi * double(m) / (2.0 * double(n))));
}

void dctForward(std::span<const float> table, std::span<const float> x, std::span<float> X) noexcept {
  const int n = int(x.size()), period = 4 * n;
  const float s0 = std::sqrt(1.0f / float(n)), s = std::sqrt(2.0f / float(n));
  for (int k = 0; k < n; ++k) {
    // Phase index (2i + 1) k mod 4n, advanced by 2k per sample.
    const int step = (2 * k) % period;
    int m = k % period;
    float sum = 0.0f;
    for (int i = 0; i < n; ++i) {
      sum += x[std::size_t(i)] * table[std::size_t(m)];
      m += step;
      if (m >= period) m -= period;
    }
    X[std::size_t(k)] = sum * (k == 0 ? s0 : s);
  }
}

void dctInverse(std::span<const float> table, std::span<const float> X, int end, std::span<float> x) noexcept {
  const int n = int(x.size()), period = 4 * n;
  const float s0 = std::sqrt(1.0f / float(n)), s = std::sqrt(2.0f / float(n));
  for (float& v : x) v = 0.0f;
  for (int k = 0; k < end && k < n; ++k) {
    const float c = X[std::size_t(k)] * (k == 0 ? s0 : s);
    if (c == 0.0f) continue;  // most coefficients of a coded block are zero
    const int step = (2 * k) % period;
    int m = k % period;
    for (int i = 0; i < n; ++i) {
      x[std::size_t(i)] += c * table[std::size_t(m)];
      m += step;
      if (m >= period) m -= period;
    }
  }
}

}  // namespace vt::haptics::codec
