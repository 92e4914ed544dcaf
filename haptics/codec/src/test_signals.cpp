#include "vt/haptics/codec/test_signals.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <numbers>
#include <limits>
#include <random>
#include <span>

#include "vt/core/error.hpp"
#include "vt/haptics/codec/spqi.hpp"

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

CodecReport evaluateCodec(const CodecConfig& config, const std::vector<std::vector<float>>& channels) {
  using Clock = std::chrono::steady_clock;
  if (int(channels.size()) != config.channels) fail("evaluateCodec: ", channels.size(), " signals for ", config.channels, " channels");
  const auto encoder = makeBlockEncoder(config);
  const auto decoder = makeBlockDecoder(config);
  const auto frameLength = std::size_t(config.frameLength);
  const std::size_t samples = channels[0].size();
  const std::size_t blockSamples = frameLength * std::size_t(decoder->frameCount());
  const std::size_t usable = samples / blockSamples * blockSamples;
  std::vector<std::vector<float>> decoded(channels.size(), std::vector<float>(usable, 0.0f));
  std::size_t totalBytes = 0, blocks = 0;
  Clock::duration encodeTime{}, decodeTime{};
  for (std::size_t start = 0; start < usable; start += blockSamples) {
    Clock::duration encodeBlock{};
    for (std::size_t f = start; f < start + blockSamples; f += frameLength) {
      WaveBlock frame{};
      for (std::size_t c = 0; c < channels.size(); ++c)
        std::copy_n(channels[c].begin() + std::ptrdiff_t(f), frameLength, frame[c].begin());
      const auto t0 = Clock::now();
      encoder->push(frame);
      encodeBlock += Clock::now() - t0;
    }
    const auto packet = encoder->packet();
    const auto t1 = Clock::now();
    const bool ok = decoder->decode(packet);
    decodeTime += Clock::now() - t1;
    encodeTime += encodeBlock;
    if (!ok) fail("codec ", codecName(config.id), " rejected its own block at sample ", start);
    totalBytes += packet.size();
    ++blocks;
    for (int i = 0; i < decoder->frameCount(); ++i)
      for (std::size_t c = 0; c < channels.size(); ++c)
        std::copy_n(decoder->frame(i)[c].begin(), frameLength,
                    decoded[c].begin() + std::ptrdiff_t(start + std::size_t(i) * frameLength));
  }
  CodecReport report;
  std::vector<float> allReference, allDecoded;
  for (std::size_t c = 0; c < channels.size(); ++c) {
    allReference.insert(allReference.end(), channels[c].begin(), channels[c].begin() + std::ptrdiff_t(usable));
    allDecoded.insert(allDecoded.end(), decoded[c].begin(), decoded[c].end());
  }
  report.snr_db = snr_db(allReference, allDecoded);
  report.spqi = std::numeric_limits<double>::quiet_NaN();
  if (usable >= std::size_t(kSpqiBlock)) {
    report.spqi = 0.0;
    for (std::size_t c = 0; c < channels.size(); ++c)
      report.spqi += spqi(std::span(channels[c]).first(usable), decoded[c], double(config.sampleRate_hz));
    report.spqi /= double(channels.size());
  }
  const double pcmBytes = double(usable) * double(channels.size()) * 2.0;
  report.ratio = totalBytes ? pcmBytes / double(totalBytes) : 0.0;
  const auto us = [&](Clock::duration d) { return blocks ? std::chrono::duration<double, std::micro>(d).count() / double(blocks) : 0.0; };
  report.encode_us_per_block = us(encodeTime);
  report.decode_us_per_block = us(decodeTime);
  const double seconds = double(usable) / double(config.sampleRate_hz);
  report.bitrate_kbps = seconds > 0 ? double(totalBytes) * 8.0 / seconds / 1000.0 / double(channels.size()) : 0.0;
  report.decoded = std::move(decoded[0]);
  return report;
}

CodecReport evaluateCodec(const CodecConfig& config, const std::vector<float>& signal) {
  return evaluateCodec(config, std::vector<std::vector<float>>(std::size_t(std::max(config.channels, 0)), signal));
}

}  // namespace vt::haptics
