#include "vt/haptics/codec/test_signals.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <numbers>
#include <random>

#include "vt/core/error.hpp"

namespace vt::haptics {

namespace {

constexpr float kTwoPi = 2.0f * std::numbers::pi_v<float>;

float hash01(int x, int y) noexcept {
  std::uint32_t h = std::uint32_t(x) * 374761393u + std::uint32_t(y) * 668265263u;
  h = (h ^ (h >> 13)) * 1274126177u;
  return float((h ^ (h >> 16)) & 0xFFFFFFu) / float(0xFFFFFF);
}

float smooth(float t) noexcept { return t * t * (3.0f - 2.0f * t); }

}  // namespace

std::vector<float> sineSignal(float frequency_hz, float amplitude, int samples, int sampleRate_hz) {
  std::vector<float> out(std::size_t(std::max(samples, 0)));
  for (std::size_t i = 0; i < out.size(); ++i)
    out[i] = amplitude * std::sin(kTwoPi * frequency_hz * float(i) / float(sampleRate_hz));
  return out;
}

std::vector<float> bandNoiseSignal(float lo_hz, float hi_hz, float rms, int samples, int sampleRate_hz,
                                   std::uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  constexpr int kComponents = 96;
  std::vector<double> out(std::size_t(std::max(samples, 0)), 0.0);
  for (int k = 0; k < kComponents; ++k) {
    const float f = lo_hz + (hi_hz - lo_hz) * unit(rng);
    const float phase = kTwoPi * unit(rng);
    for (std::size_t i = 0; i < out.size(); ++i) out[i] += std::sin(kTwoPi * f * float(i) / float(sampleRate_hz) + phase);
  }
  double energy = 0.0;
  for (double v : out) energy += v * v;
  const double scale = out.empty() || energy == 0.0 ? 0.0 : rms / std::sqrt(energy / double(out.size()));
  std::vector<float> result(out.size());
  for (std::size_t i = 0; i < out.size(); ++i) result[i] = std::clamp(float(out[i] * scale), -1.0f, 1.0f);
  return result;
}

float textureHeight(float x_m, float y_m) noexcept {
  // Stripes 2 mm apart with sharpened edges, plus value noise on a 0.25 mm grid.
  const float stripe = 0.5f + 0.5f * std::tanh(3.0f * std::sin(kTwoPi * x_m / 0.002f));
  const float gx = x_m / 0.00025f, gy = y_m / 0.00025f;
  const int ix = int(std::floor(gx)), iy = int(std::floor(gy));
  const float fx = smooth(gx - float(ix)), fy = smooth(gy - float(iy));
  const float top = hash01(ix, iy) + (hash01(ix + 1, iy) - hash01(ix, iy)) * fx;
  const float bottom = hash01(ix, iy + 1) + (hash01(ix + 1, iy + 1) - hash01(ix, iy + 1)) * fx;
  const float noise = top + (bottom - top) * fy;
  return 0.6f * stripe + 0.4f * noise;
}

std::vector<float> textureSweepSignal(float speedStart_m_s, float speedEnd_m_s, float amplitude, int samples,
                                      int sampleRate_hz) {
  std::vector<float> out(std::size_t(std::max(samples, 0)));
  const float dt = 1.0f / float(sampleRate_hz);
  float x = 0.0f;
  for (std::size_t i = 0; i < out.size(); ++i) {
    const float t = out.size() > 1 ? float(i) / float(out.size() - 1) : 0.0f;
    x += (speedStart_m_s + (speedEnd_m_s - speedStart_m_s) * t) * dt;
    out[i] = textureHeight(x, 0.01f + 0.002f * t);
  }
  double mean = 0.0;
  for (float v : out) mean += v;
  mean /= double(std::max<std::size_t>(out.size(), 1));
  float peak = 1e-9f;
  for (float& v : out) {
    v -= float(mean);
    peak = std::max(peak, std::fabs(v));
  }
  for (float& v : out) v *= amplitude / peak;
  return out;
}

double snr_db(const std::vector<float>& reference, const std::vector<float>& test) {
  double signal = 0.0, noise = 0.0;
  for (std::size_t i = 0; i < reference.size(); ++i) {
    const double r = reference[i], d = r - (i < test.size() ? test[i] : 0.0f);
    signal += r * r;
    noise += d * d;
  }
  if (noise == 0.0) return 200.0;
  return 10.0 * std::log10(signal / noise);
}

CodecReport evaluateCodec(const TactileCodec& codec, const std::vector<float>& signal, int blockLength,
                          int sampleRate_hz, int channels) {
  using Clock = std::chrono::steady_clock;
  CodecReport report;
  report.decoded.assign(signal.size(), 0.0f);
  const BlockFormat format{channels, blockLength, sampleRate_hz};
  std::array<std::uint8_t, kMaxEncodedBlock> bytes{};
  std::size_t totalBytes = 0, blocks = 0;
  Clock::duration encodeTime{}, decodeTime{};
  for (std::size_t start = 0; start + std::size_t(blockLength) <= signal.size(); start += std::size_t(blockLength)) {
    WaveBlock block{}, decoded{};
    for (int c = 0; c < channels; ++c)
      for (int i = 0; i < blockLength; ++i) block[std::size_t(c)][std::size_t(i)] = signal[start + std::size_t(i)];
    const auto t0 = Clock::now();
    const std::size_t size = codec.encode(block, format, bytes);
    const auto t1 = Clock::now();
    const bool ok = codec.decode(std::span(bytes.data(), size), format, decoded);
    const auto t2 = Clock::now();
    if (!ok) fail("codec ", codecName(codec.id()), " rejected its own block at sample ", start);
    encodeTime += t1 - t0;
    decodeTime += t2 - t1;
    totalBytes += size;
    ++blocks;
    for (int i = 0; i < blockLength; ++i) report.decoded[start + std::size_t(i)] = decoded[0][std::size_t(i)];
  }
  const double pcmBytes = double(blocks) * blockLength * channels * 2.0;
  report.ratio = totalBytes ? pcmBytes / double(totalBytes) : 0.0;
  report.snr_db = snr_db(signal, report.decoded);
  const auto us = [&](Clock::duration d) { return blocks ? std::chrono::duration<double, std::micro>(d).count() / double(blocks) : 0.0; };
  report.encode_us_per_block = us(encodeTime);
  report.decode_us_per_block = us(decodeTime);
  const double seconds = double(blocks) * blockLength / double(sampleRate_hz);
  report.bitrate_kbps = seconds > 0 ? double(totalBytes) * 8.0 / seconds / 1000.0 / channels : 0.0;
  return report;
}

}  // namespace vt::haptics
