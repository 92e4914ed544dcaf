// Perceptual vibrotactile codec in the spirit of the IEEE P1918.1.1 proposals: per channel a
// CDF 9/7 DWT, a psychohaptic model (vibrotactileThreshold_db) that scales each band's
// quantisation step by how insensitive the skin is at that band's frequency, a block gain
// (the signal masks noise relative to its own level), and context-adaptive binary range coding.
// Each block stands alone (contexts start fresh), so a lost packet never corrupts the next one.
#include <algorithm>
#include <array>
#include <bit>
#include <cmath>

#include "codec_internal.hpp"
#include "dwt.hpp"
#include "range_coder.hpp"
#include "vt/haptics/codec/psychohaptic.hpp"

namespace vt::haptics::codec {

namespace {

constexpr int kBands = kMaxDwtLevels + 1;
constexpr int kGainBits = 6;
constexpr float kGainStepsPerOctave = 3.0f;  // 2 dB gain resolution
constexpr float kSilentRms = 1e-4f;          // -80 dBFS: below 16-bit PCM's noise floor
constexpr float kDeadzone = 0.2f;            // rounding offset 0.3 instead of 0.5: cheaper zeros
constexpr int kMaxEgPrefix = 16;
// How strongly the threshold curve shapes the noise (0 = flat noise, 1 = the full curve).
constexpr float kShapingStrength = 0.3f;

struct Contexts {
  BitModel active{0.5f};
  std::array<BitModel, 1 << kGainBits> gain{};
  std::array<BitModel, kBands> bandNonzero{};
  std::array<std::array<BitModel, 2>, kBands> significant{};
  std::array<std::array<BitModel, 2>, kBands> magnitude{};
  std::array<BitModel, kMaxEgPrefix + 1> egPrefix{};
  Contexts() {
    for (auto& s : significant) s = {BitModel(0.6f), BitModel(0.4f)};
  }
};

float gainFromCode(int code) noexcept { return std::exp2(float(code - ((1 << kGainBits) - 1)) / kGainStepsPerOctave); }

int gainCode(float rms) noexcept {
  const float code = std::round(std::log2(rms) * kGainStepsPerOctave) + float((1 << kGainBits) - 1);
  return int(std::clamp(code, 0.0f, float((1 << kGainBits) - 1)));
}

/// Quantisation step of every band relative to the block gain.
struct StepTable {
  int levels = 0;
  std::array<float, kBands> relativeStep{};
};

StepTable stepTable(const BlockFormat& f, float baseStep) noexcept {
  StepTable table;
  table.levels = dwtLevels(f.length);
  for (int b = 0; b <= table.levels; ++b) {
    // Band b spans [lo, hi] Hz; the model is evaluated at its geometric centre.
    const float nyquist = 0.5f * float(f.sampleRate_hz);
    const int level = b == 0 ? table.levels : table.levels + 1 - b;
    const float hi = nyquist / std::exp2(float(level - 1));
    const float lo = b == 0 ? hi / 4.0f : hi / 2.0f;
    const float threshold_db = vibrotactileThreshold_db(std::sqrt(lo * hi));
    table.relativeStep[std::size_t(b)] = baseStep * std::pow(10.0f, kShapingStrength * threshold_db / 20.0f);
  }
  return table;
}


void encodeTree(RangeEncoder& rc, std::span<BitModel> tree, int value, int bits) noexcept {
  int node = 1;
  for (int i = bits - 1; i >= 0; --i) {
    const int bit = (value >> i) & 1;
    rc.bit(tree[std::size_t(node)], bit);
    node = (node << 1) | bit;
  }
}
int decodeTree(RangeDecoder& rc, std::span<BitModel> tree, int bits) noexcept {
  int node = 1;
  for (int i = 0; i < bits; ++i) node = (node << 1) | rc.bit(tree[std::size_t(node)]);
  return node - (1 << bits);
}

class PerceptualCodec final : public TactileCodec {
 public:
  explicit PerceptualCodec(int quality) noexcept
      // quality 0..100 -> target noise 6..46 dB below the block level before shaping.
      : m_baseStep(std::sqrt(12.0f) * std::pow(10.0f, -(6.0f + 0.4f * float(quality)) / 20.0f)) {}

  CodecId id() const noexcept override { return CodecId::Perceptual; }

  std::size_t encode(const WaveBlock& block, const BlockFormat& f, std::span<std::uint8_t> out) const noexcept override {
    if (!validFormat(f)) return 0;
    const StepTable table = stepTable(f, m_baseStep);
    Contexts ctx;
    RangeEncoder rc(out);
    for (int c = 0; c < f.channels; ++c) {
      std::array<float, kMaxBlockSamples> x{};
      double energy = 0.0;
      for (int i = 0; i < f.length; ++i) {
        const float v = block[std::size_t(c)][std::size_t(i)];
        x[std::size_t(i)] = std::isfinite(v) ? std::clamp(v, -1.0f, 1.0f) : 0.0f;
        energy += double(x[std::size_t(i)]) * x[std::size_t(i)];
      }
      const float rms = float(std::sqrt(energy / f.length));
      if (rms < kSilentRms) {
        rc.bit(ctx.active, 0);
        continue;
      }
      const int code = gainCode(rms);
      const float gain = gainFromCode(code);
      std::array<int, kMaxBlockSamples> q{};
      dwtForward(std::span(x.data(), std::size_t(f.length)), table.levels);
      bool any = false;
      for (int b = 0; b <= table.levels; ++b) {
        int start = 0, size = 0;
        dwtBand(f.length, table.levels, b, start, size);
        const float step = gain * table.relativeStep[std::size_t(b)];
        for (int i = start; i < start + size; ++i) {
          const float m = std::floor(std::fabs(x[std::size_t(i)]) / step + 0.5f - kDeadzone);
          const int mag = int(std::min(m, float(1 << kMaxEgPrefix)));
          q[std::size_t(i)] = x[std::size_t(i)] < 0.0f ? -mag : mag;
          any = any || mag != 0;
        }
      }
      rc.bit(ctx.active, any ? 1 : 0);
      if (!any) continue;
      encodeTree(rc, ctx.gain, code, kGainBits);
      for (int b = 0; b <= table.levels; ++b) encodeBand(rc, ctx, b, q, f.length, table.levels);
    }
    return rc.finish();
  }

  bool decode(std::span<const std::uint8_t> data, const BlockFormat& f, WaveBlock& block) const noexcept override {
    block = {};
    if (!validFormat(f)) return false;
    const StepTable table = stepTable(f, m_baseStep);
    Contexts ctx;
    RangeDecoder rc(data);
    for (int c = 0; c < f.channels; ++c) {
      if (!rc.bit(ctx.active)) continue;
      const float gain = gainFromCode(decodeTree(rc, ctx.gain, kGainBits));
      std::array<float, kMaxBlockSamples> x{};
      for (int b = 0; b <= table.levels; ++b) {
        int start = 0, size = 0;
        dwtBand(f.length, table.levels, b, start, size);
        const float step = gain * table.relativeStep[std::size_t(b)];
        std::array<int, kMaxBlockSamples> q{};
        decodeBand(rc, ctx, b, q, start, size);
        for (int i = start; i < start + size; ++i) x[std::size_t(i)] = float(q[std::size_t(i)]) * step;
      }
      dwtInverse(std::span(x.data(), std::size_t(f.length)), table.levels);
      for (int i = 0; i < f.length; ++i) block[std::size_t(c)][std::size_t(i)] = std::clamp(x[std::size_t(i)], -1.0f, 1.0f);
    }
    return true;
  }

 private:
  static bool validFormat(const BlockFormat& f) noexcept {
    return f.channels >= 1 && f.channels <= kMaxActuators && f.length >= 1 && f.length <= kMaxBlockSamples &&
           f.sampleRate_hz >= 1 && f.sampleRate_hz <= 96000;
  }

  static void encodeBand(RangeEncoder& rc, Contexts& ctx, int b, const std::array<int, kMaxBlockSamples>& q,
                         int length, int levels) noexcept {
    int start = 0, size = 0;
    dwtBand(length, levels, b, start, size);
    bool nonzero = false;
    for (int i = start; i < start + size; ++i) nonzero = nonzero || q[std::size_t(i)] != 0;
    const auto band = std::size_t(b);
    rc.bit(ctx.bandNonzero[band], nonzero ? 1 : 0);
    if (!nonzero) return;
    int previous = 0;
    bool seen = false;
    for (int i = start; i < start + size; ++i) {
      const int value = q[std::size_t(i)];
      const int mag = std::abs(value);
      // The last coefficient of a band flagged nonzero is significant if none was before.
      if (seen || i + 1 < start + size) rc.bit(ctx.significant[band][std::size_t(previous)], mag != 0);
      previous = mag != 0;
      if (!mag) continue;
      seen = true;
      rc.direct(value < 0);
      rc.bit(ctx.magnitude[band][0], mag > 1);
      if (mag == 1) continue;
      rc.bit(ctx.magnitude[band][1], mag > 2);
      if (mag == 2) continue;
      // Exp-Golomb of mag - 3: prefix k (adaptive unary), then k raw bits.
      const unsigned rest = unsigned(mag - 3) + 1;
      const int k = std::bit_width(rest) - 1;
      for (int j = 0; j < k; ++j) rc.bit(ctx.egPrefix[std::size_t(j)], 1);
      if (k < kMaxEgPrefix) rc.bit(ctx.egPrefix[std::size_t(k)], 0);
      for (int j = k - 1; j >= 0; --j) rc.direct(int((rest >> j) & 1u));
    }
  }

  static void decodeBand(RangeDecoder& rc, Contexts& ctx, int b, std::array<int, kMaxBlockSamples>& q, int start,
                         int size) noexcept {
    const auto band = std::size_t(b);
    if (!rc.bit(ctx.bandNonzero[band])) return;
    int previous = 0;
    bool seen = false;
    for (int i = start; i < start + size; ++i) {
      const bool significant =
          (seen || i + 1 < start + size) ? rc.bit(ctx.significant[band][std::size_t(previous)]) != 0 : true;
      previous = significant;
      if (!significant) continue;
      seen = true;
      const bool negative = rc.direct() != 0;
      int mag = 1;
      if (rc.bit(ctx.magnitude[band][0])) {
        mag = 2;
        if (rc.bit(ctx.magnitude[band][1])) {
          int k = 0;
          while (k < kMaxEgPrefix && rc.bit(ctx.egPrefix[std::size_t(k)])) ++k;
          unsigned rest = 1;
          for (int j = 0; j < k; ++j) rest = (rest << 1) | unsigned(rc.direct());
          mag = int(rest - 1) + 3;
        }
      }
      q[std::size_t(i)] = negative ? -mag : mag;
    }
  }

  float m_baseStep;
};

}  // namespace

std::unique_ptr<TactileCodec> makePerceptual(int quality) { return std::make_unique<PerceptualCodec>(quality); }

}  // namespace vt::haptics::codec
