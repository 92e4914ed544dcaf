#include "dct.hpp"

#include <cmath>
#include <complex>
#include <numbers>
#include <utility>

namespace vt::haptics::codec {

namespace {

using Complex = std::complex<float>;

bool useFft(int n) noexcept { return n >= 4 && (n & (n - 1)) == 0; }

// FFT layout of the table: n/2 twiddles e^(-2 pi i j / n), then n rotations e^(-i pi k / 2n),
// as interleaved (re, im) pairs: 3n floats.
const Complex* twiddles(std::span<const float> table) noexcept { return reinterpret_cast<const Complex*>(table.data()); }
const Complex* rotations(std::span<const float> table, int n) noexcept {
  return reinterpret_cast<const Complex*>(table.data() + n);
}

/// In-place radix-2 FFT of a[0..n); inverse = conjugate twiddles (unscaled).
void fft(Complex* a, int n, const Complex* w, bool inverse) noexcept {
  for (int i = 1, j = 0; i < n; ++i) {
    int bit = n >> 1;
    for (; j & bit; bit >>= 1) j ^= bit;
    j ^= bit;
    if (i < j) std::swap(a[i], a[j]);
  }
  for (int len = 2; len <= n; len <<= 1) {
    const int stride = n / len;
    for (int i = 0; i < n; i += len) {
      for (int k = 0; k < len / 2; ++k) {
        const Complex t = (inverse ? std::conj(w[k * stride]) : w[k * stride]) * a[i + k + len / 2];
        a[i + k + len / 2] = a[i + k] - t;
        a[i + k] += t;
      }
    }
  }
}

float scale(int k, int n) noexcept { return std::sqrt((k == 0 ? 1.0f : 2.0f) / float(n)); }

}  // namespace

void makeDctTable(int n, std::span<float> table) noexcept {
  if (useFft(n)) {
    for (int j = 0; j < n / 2; ++j) {
      const double a = -2.0 * std::numbers::pi * j / n;
      table[std::size_t(2 * j)] = float(std::cos(a));
      table[std::size_t(2 * j + 1)] = float(std::sin(a));
    }
    for (int k = 0; k < n; ++k) {
      const double a = -std::numbers::pi * k / (2.0 * n);
      table[std::size_t(n + 2 * k)] = float(std::cos(a));
      table[std::size_t(n + 2 * k + 1)] = float(std::sin(a));
    }
    return;
  }
  for (int m = 0; m < 4 * n; ++m)
    table[std::size_t(m)] = float(std::cos(std::numbers::pi * double(m) / (2.0 * double(n))));
}

void dctForward(std::span<const float> table, std::span<const float> x, std::span<float> X,
                std::span<float> work) noexcept {
  const int n = int(x.size()), period = 4 * n;
  if (useFft(n)) {
    auto* v = reinterpret_cast<Complex*>(work.data());
    for (int i = 0; i < n / 2; ++i) {
      v[i] = x[std::size_t(2 * i)];
      v[n - 1 - i] = x[std::size_t(2 * i + 1)];
    }
    fft(v, n, twiddles(table), false);
    const Complex* r = rotations(table, n);
    for (int k = 0; k < n; ++k) X[std::size_t(k)] = (r[k] * v[k]).real() * scale(k, n);
    return;
  }
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
    X[std::size_t(k)] = sum * scale(k, n);
  }
}

void dctInverse(std::span<const float> table, std::span<const float> X, int end, std::span<float> x,
                std::span<float> work) noexcept {
  const int n = int(x.size()), period = 4 * n;
  if (useFft(n)) {
    auto* v = reinterpret_cast<Complex*>(work.data());
    const Complex* r = rotations(table, n);
    auto y = [&](int k) { return k < end && k < n ? X[std::size_t(k)] / scale(k, n) : 0.0f; };
    for (int k = 0; k < n; ++k) v[k] = std::conj(r[k]) * Complex(y(k), k == 0 ? 0.0f : -y(n - k));
    fft(v, n, twiddles(table), true);
    for (int i = 0; i < n / 2; ++i) {
      x[std::size_t(2 * i)] = v[i].real() / float(n);
      x[std::size_t(2 * i + 1)] = v[n - 1 - i].real() / float(n);
    }
    return;
  }
  for (float& v : x) v = 0.0f;
  for (int k = 0; k < end && k < n; ++k) {
    const float c = X[std::size_t(k)] * scale(k, n);
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
