// Perceptual vibrotactile block coder in the spirit of the IEEE P1918.1.1 proposals, per
// channel: a DCT of the whole block (longer blocks resolve partials into fewer coefficients),
// a psychohaptic model (vibrotactileThreshold_db) scaling each octave band's quantiser step by
// how insensitive the skin is there, a block gain (the signal masks noise relative to its own
// level), a prediction of each channel's coefficients from the previous channel's decoded
// ones (per-band weights: glove actuators are correlated), and context-adaptive binary range
// coding whose contexts carry across the channels of the block. Blocks stand alone.
#include "perceptual_coder.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>

#include "dct.hpp"
#include "range_coder.hpp"
#include "vt/haptics/codec/psychohaptic.hpp"

namespace vt::haptics::codec {

namespace {

constexpr int kGainBits = 6;
constexpr float kGainStepsPerOctave = 3.0f;  // 2 dB gain resolution
constexpr float kSilentRms = 1e-4f;          // -80 dBFS: below 16-bit PCM's noise floor
constexpr float kDeadzone = 0.2f;            // rounding offset 0.3 instead of 0.5: cheaper zeros
constexpr int kMaxEgPrefix = 16;
// How strongly the threshold curve shapes the noise (0 = flat noise, 1 = the full curve).
constexpr float kShapingStrength = 0.3f;
constexpr int kMaxBands = 14;        // octave bands of the coefficient index: bit_width(k) < 14
constexpr int kPositionClasses = 6;  // octaves of frequency relative to a 32-sample block
constexpr int kWidthBits = 4;        // bit width of the coded length, 0..13
// Weight of the prediction from the previous channel: (code + 1) / 16, 1/16..2.
constexpr int kWeightBits = 5;
float weightFromCode(int code) noexcept { return float(code + 1) / 16.0f; }
// Prediction is used when it leaves at most this share of a channel's energy.
constexpr float kPredictGain = 0.7f;

struct Contexts {
  BitModel active{0.5f};
  std::array<BitModel, 1 << kGainBits> gain{};
  std::array<BitModel, 2> gainSame{BitModel(0.4f), BitModel(0.5f)};
  std::array<BitModel, (1 << kGainBits)> gainDelta{};
  BitModel predicted{0.5f};
  std::array<BitModel, 1 << kWeightBits> weight{};
  std::array<BitModel, kMaxBands> bandPredicted{};
  std::array<BitModel, 1 << kWidthBits> width{};
  std::array<std::array<BitModel, 4>, kPositionClasses> significant{};
  std::array<std::array<BitModel, 3>, kPositionClasses> greater1{};
  std::array<BitModel, kPositionClasses> greater2{};
  std::array<BitModel, kMaxEgPrefix + 1> egPrefix{};
  Contexts() {
    for (auto& s : significant) s = {BitModel(0.75f), BitModel(0.55f), BitModel(0.45f), BitModel(0.35f)};
  }
};

float gainFromCode(int code) noexcept { return std::exp2(float(code - ((1 << kGainBits) - 1)) / kGainStepsPerOctave); }

int gainCode(float rms) noexcept {
  const float code = std::round(std::log2(rms) * kGainStepsPerOctave) + float((1 << kGainBits) - 1);
  return int(std::clamp(code, 0.0f, float((1 << kGainBits) - 1)));
}

int bandOf(int k) noexcept { return std::bit_width(unsigned(k)); }
int bandCount(int length) noexcept { return bandOf(length - 1) + 1; }

/// Quantiser step per octave band relative to the block gain, from the band's centre frequency.
std::array<float, kMaxBands> stepTable(const BlockShape& shape, float baseStep) noexcept {
  std::array<float, kMaxBands> steps{};
  const int bands = bandCount(shape.length);
  const float binHz = 0.5f * float(shape.sampleRate_hz) / float(shape.length);
  for (int b = 0; b < bands; ++b) {
    const int lo = b == 0 ? 0 : 1 << (b - 1), hi = std::min(shape.length, 1 << b) - 1;
    const float centre_hz = std::sqrt((float(lo) + 0.5f) * (float(hi) + 0.5f)) * binHz;
    steps[std::size_t(b)] = baseStep * std::pow(10.0f, kShapingStrength * vibrotactileThreshold_db(centre_hz) / 20.0f);
  }
  return steps;
}

int positionClass(int k, int length) noexcept {
  return std::min(kPositionClasses - 1, bandOf(int(std::int64_t(k) * 32 / length)));
}
int neighbourhood(std::span<const int> q, int k) noexcept {
  const int a = k >= 1 ? std::min(2, std::abs(q[std::size_t(k - 1)])) : 0;
  const int b = k >= 2 ? std::min(1, std::abs(q[std::size_t(k - 2)])) : 0;
  return a + b;
}
int adaptShift(const BlockShape& shape) noexcept { return shape.channels * shape.length <= 64 ? 4 : 5; }

template <class Coder>
void codeTree(Coder& rc, std::span<BitModel> tree, int& value, int bits) noexcept {
  int node = 1;
  for (int i = bits - 1; i >= 0; --i) {
    int bit = (value >> i) & 1;
    if constexpr (std::is_same_v<Coder, RangeEncoder>) rc.bit(tree[std::size_t(node)], bit);
    else bit = rc.bit(tree[std::size_t(node)]);
    node = (node << 1) | bit;
  }
  value = node - (1 << bits);
}

// One routine for both directions keeps the bit stream's syntax in one place: the encoder
// passes the values to write, the decoder receives the values read.
template <class Coder>
void codeCoefficients(Coder& rc, Contexts& ctx, std::span<int> q, int end, int length) noexcept {
  constexpr bool kEncode = std::is_same_v<Coder, RangeEncoder>;
  for (int k = 0; k < end; ++k) {
    const int pc = positionClass(k, length), nb = neighbourhood(q, k);
    int mag = kEncode ? std::abs(q[std::size_t(k)]) : 0;
    bool significant = true;  // the last coefficient before `end` is nonzero by definition
    if (k + 1 < end) {
      auto& model = ctx.significant[std::size_t(pc)][std::size_t(nb)];
      if constexpr (kEncode) rc.bit(model, mag != 0);
      else significant = rc.bit(model) != 0;
      if constexpr (kEncode) significant = mag != 0;
    }
    if (!significant) {
      q[std::size_t(k)] = 0;
      continue;
    }
    int negative = kEncode ? int(q[std::size_t(k)] < 0) : 0;
    if constexpr (kEncode) rc.direct(negative);
    else negative = rc.direct();
    auto& g1 = ctx.greater1[std::size_t(pc)][std::size_t(std::min(nb, 2))];
    bool more = kEncode ? mag > 1 : false;
    if constexpr (kEncode) rc.bit(g1, more);
    else more = rc.bit(g1) != 0;
    if (more) {
      auto& g2 = ctx.greater2[std::size_t(pc)];
      bool more2 = kEncode ? mag > 2 : false;
      if constexpr (kEncode) rc.bit(g2, more2);
      else more2 = rc.bit(g2) != 0;
      if (!more2) {
        mag = 2;
      } else {
        // Exp-Golomb of mag - 3: prefix k (adaptive unary), then k raw bits.
        unsigned rest = kEncode ? unsigned(mag - 3) + 1 : 1;
        const int bits = kEncode ? std::bit_width(rest) - 1 : 0;
        int prefix = 0;
        if constexpr (kEncode) {
          for (int j = 0; j < bits; ++j) rc.bit(ctx.egPrefix[std::size_t(j)], 1);
          if (bits < kMaxEgPrefix) rc.bit(ctx.egPrefix[std::size_t(bits)], 0);
          for (int j = bits - 1; j >= 0; --j) rc.direct(int((rest >> j) & 1u));
        } else {
          while (prefix < kMaxEgPrefix && rc.bit(ctx.egPrefix[std::size_t(prefix)])) ++prefix;
          for (int j = 0; j < prefix; ++j) rest = (rest << 1) | unsigned(rc.direct());
          mag = int(rest - 1) + 3;
        }
      }
    } else {
      mag = 1;
    }
    q[std::size_t(k)] = negative ? -mag : mag;
  }
}

// The gain: a bit tree for the first active channel, then the difference to the previous
// active channel's (sign raw, magnitude in adaptive unary): the fingers of a slide share levels.
template <class Coder>
void codeGain(Coder& rc, Contexts& ctx, int& code, int previousCode) noexcept {
  constexpr bool kEncode = std::is_same_v<Coder, RangeEncoder>;
  if (previousCode < 0) {
    codeTree(rc, ctx.gain, code, kGainBits);
    return;
  }
  const int delta = kEncode ? code - previousCode : 0;
  int same = delta == 0;
  if constexpr (kEncode) rc.bit(ctx.gainSame[0], same);
  else same = rc.bit(ctx.gainSame[0]);
  if (same) {
    code = previousCode;
    return;
  }
  int negative = delta < 0;
  if constexpr (kEncode) rc.direct(negative);
  else negative = rc.direct();
  int magnitude = 1;
  const int limit = negative ? previousCode : (1 << kGainBits) - 1 - previousCode;
  if constexpr (kEncode) {
    for (magnitude = 1; magnitude < std::abs(delta); ++magnitude) rc.bit(ctx.gainDelta[std::size_t(magnitude)], 1);
    if (magnitude < limit) rc.bit(ctx.gainDelta[std::size_t(magnitude)], 0);
  } else {
    while (magnitude < limit && rc.bit(ctx.gainDelta[std::size_t(magnitude)])) ++magnitude;
  }
  code = std::clamp(previousCode + (negative ? -magnitude : magnitude), 0, (1 << kGainBits) - 1);
}

template <class Coder>
void codeLength(Coder& rc, Contexts& ctx, int& end) noexcept {
  constexpr bool kEncode = std::is_same_v<Coder, RangeEncoder>;
  int width = kEncode ? std::bit_width(unsigned(end)) : 0;
  codeTree(rc, ctx.width, width, kWidthBits);
  if (width == 0) {
    end = 0;
    return;
  }
  int value = kEncode ? end : 1;
  for (int j = width - 2; j >= 0; --j) {
    if constexpr (kEncode) rc.direct((value >> j) & 1);
    else value = (value << 1) | rc.direct();
  }
  end = value;
}

}  // namespace

float perceptualBaseStep(int quality) noexcept {
  // quality 0..100 -> target noise 6..46 dB below the block level before shaping.
  return std::sqrt(12.0f) * std::pow(10.0f, -(6.0f + 0.4f * float(quality)) / 20.0f);
}

std::size_t encodePerceptual(std::span<const float> dctTable, float baseStep, const BlockShape& shape,
                             const float* samples, CoderScratch s, std::span<std::uint8_t> out,
                             bool& overflow) noexcept {
  const auto n = std::size_t(shape.length);
  const int bands = bandCount(shape.length);
  const auto steps = stepTable(shape, baseStep);
  Contexts ctx;
  RangeEncoder rc(out, adaptShift(shape));
  bool previousActive = false;
  int previousGain = -1;  // gain code of the last active channel
  for (int c = 0; c < shape.channels; ++c) {
    const float* x = samples + std::size_t(c) * shape.stride;
    double energy = 0.0;
    for (std::size_t i = 0; i < n; ++i) {
      s.time[i] = std::isfinite(x[i]) ? std::clamp(x[i], -1.0f, 1.0f) : 0.0f;
      energy += double(s.time[i]) * s.time[i];
    }
    const float rms = float(std::sqrt(energy / double(n)));
    auto silent = [&] {
      rc.bit(ctx.active, 0);
      std::fill_n(s.previous.begin(), n, 0.0f);
      previousActive = false;
    };
    if (rms < kSilentRms) {
      silent();
      continue;
    }
    dctForward(dctTable, s.time.first(n), s.coeff.first(n));
    int code = gainCode(rms);
    const float gain = gainFromCode(code);
    // One weight for the channel (least squares), used in the bands where it leaves less energy.
    int weightCode = 0;
    std::array<float, kMaxBands> weight{};
    bool predicted = false;
    if (previousActive) {
      double cross = 0.0, power = 0.0;
      for (std::size_t k = 0; k < n; ++k) {
        cross += double(s.coeff[k]) * s.previous[k];
        power += double(s.previous[k]) * s.previous[k];
      }
      weightCode = std::clamp(int(std::lround(16.0 * cross / std::max(power, 1e-30))) - 1, 0, (1 << kWeightBits) - 1);
      const float w = weightFromCode(weightCode);
      double before = 0.0, after = 0.0;
      for (int b = 0; b < bands; ++b) {
        const int lo = b == 0 ? 0 : 1 << (b - 1), hi = std::min(shape.length, 1 << b);
        double plain = 0.0, residual = 0.0;
        for (int k = lo; k < hi; ++k) {
          const double v = s.coeff[std::size_t(k)], r = v - w * s.previous[std::size_t(k)];
          plain += v * v;
          residual += r * r;
        }
        if (residual < plain) weight[std::size_t(b)] = w;
        before += plain;
        after += std::min(plain, residual);
      }
      predicted = cross > 0.0 && after < kPredictGain * before;
      if (!predicted) weight.fill(0.0f);
    }
    int end = 0;
    for (std::size_t k = 0; k < n; ++k) {
      const int b = bandOf(int(k));
      const float prediction = weight[std::size_t(b)] * s.previous[k];
      const float step = gain * steps[std::size_t(b)];
      const float r = s.coeff[k] - prediction;
      const int mag = int(std::min(std::floor(std::fabs(r) / step + 0.5f - kDeadzone), float(1 << kMaxEgPrefix)));
      s.q[k] = r < 0.0f ? -mag : mag;
      s.current[k] = prediction + float(s.q[k]) * step;
      if (mag != 0) end = int(k) + 1;
    }
    if (!predicted && end == 0) {
      silent();
      continue;
    }
    rc.bit(ctx.active, 1);
    codeGain(rc, ctx, code, previousGain);
    previousGain = code;
    if (previousActive) {
      rc.bit(ctx.predicted, predicted);
      if (predicted) {
        codeTree(rc, ctx.weight, weightCode, kWeightBits);
        for (int b = 0; b < bands; ++b) rc.bit(ctx.bandPredicted[std::size_t(b)], weight[std::size_t(b)] != 0.0f);
      }
    }
    codeLength(rc, ctx, end);
    codeCoefficients(rc, ctx, s.q, end, shape.length);
    std::copy_n(s.current.begin(), n, s.previous.begin());
    previousActive = true;
  }
  const std::size_t size = rc.finish();
  overflow = size == 0 && rc.overflowed();
  return size;
}

void decodePerceptual(std::span<const float> dctTable, float baseStep, const BlockShape& shape,
                      std::span<const std::uint8_t> in, CoderScratch s, float* samples) noexcept {
  const auto n = std::size_t(shape.length);
  const int bands = bandCount(shape.length);
  const auto steps = stepTable(shape, baseStep);
  Contexts ctx;
  RangeDecoder rc(in, adaptShift(shape));
  bool previousActive = false;
  int previousGain = -1;  // gain code of the last active channel
  for (int c = 0; c < shape.channels; ++c) {
    float* x = samples + std::size_t(c) * shape.stride;
    if (!rc.bit(ctx.active)) {
      std::fill_n(x, n, 0.0f);
      std::fill_n(s.previous.begin(), n, 0.0f);
      previousActive = false;
      continue;
    }
    int code = 0;
    codeGain(rc, ctx, code, previousGain);
    previousGain = code;
    const float gain = gainFromCode(code);
    std::array<float, kMaxBands> weight{};
    if (previousActive && rc.bit(ctx.predicted)) {
      int weightCode = 0;
      codeTree(rc, ctx.weight, weightCode, kWeightBits);
      for (int b = 0; b < bands; ++b)
        if (rc.bit(ctx.bandPredicted[std::size_t(b)])) weight[std::size_t(b)] = weightFromCode(weightCode);
    }
    int end = 0;
    codeLength(rc, ctx, end);
    end = std::min(end, shape.length);
    std::fill_n(s.q.begin(), n, 0);
    codeCoefficients(rc, ctx, s.q, end, shape.length);
    int nonzeroEnd = 0;
    for (std::size_t k = 0; k < n; ++k) {
      const int b = bandOf(int(k));
      s.current[k] = weight[std::size_t(b)] * s.previous[k] +
                     float(s.q[k]) * gain * steps[std::size_t(b)];
      if (s.current[k] != 0.0f) nonzeroEnd = int(k) + 1;
    }
    dctInverse(dctTable, s.current.first(n), nonzeroEnd, std::span(x, n));
    for (std::size_t i = 0; i < n; ++i) x[i] = std::isfinite(x[i]) ? std::clamp(x[i], -1.0f, 1.0f) : 0.0f;
    std::copy_n(s.current.begin(), n, s.previous.begin());
    previousActive = true;
  }
}

}  // namespace vt::haptics::codec
