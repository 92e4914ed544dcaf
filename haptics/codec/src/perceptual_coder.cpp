// Perceptual vibrotactile block coder in the spirit of the IEEE P1918.1.1 proposals. A block
// is cut into segments (a binary tree down to 32 samples, chosen by the encoder: long segments
// resolve a steady texture's partials into few coefficients, short ones follow contact onsets
// and gaps). Per segment and channel: a DCT, a psychohaptic model (vibrotactileThreshold_db)
// scaling each octave band's quantiser step by how insensitive the skin is there, a gain (the
// signal masks noise relative to its own level), a prediction from the previous channel's
// decoded coefficients (glove actuators are correlated), and context-adaptive binary range
// coding whose contexts carry across the segments and channels of the block and start every
// block from fixed priors learned offline (context_priors.hpp). Blocks stand alone.
#include "perceptual_coder.hpp"

#include <algorithm>
#include <array>
#include <cmath>

#include "bit_syntax.hpp"
#include "dct.hpp"
#include "vt/haptics/codec/psychohaptic.hpp"

namespace vt::haptics::codec {

namespace {

using namespace syntax;

// 6 dB gain resolution: the gain only scales the quantiser step (noise within +-3 dB of the
// quality's target), so finer steps would buy nothing but bits.
constexpr float kGainStepsPerOctave = 1.0f;
constexpr float kSilentRms = 1e-4f;          // -80 dBFS: below 16-bit PCM's noise floor
constexpr float kDeadzone = 0.2f;            // rounding offset 0.3 instead of 0.5: cheaper zeros
// How strongly the threshold curve shapes the noise (0 = flat noise, 1 = the full curve).
constexpr float kShapingStrength = 0.3f;
// Prediction is used when it leaves at most this share of a channel's energy.
constexpr float kPredictGain = 0.7f;
// Rate-distortion slope of a uniform quantiser with step D: bits are worth (ln 2 / 6) D^2 each.
constexpr double kLambdaPerStep2 = 0.1155;

float gainFromCode(int code) noexcept { return std::exp2(float(code - ((1 << kGainBits) - 1)) / kGainStepsPerOctave); }
int gainCode(float rms) noexcept {
  const float code = std::round(std::log2(rms) * kGainStepsPerOctave) + float((1 << kGainBits) - 1);
  return int(std::clamp(code, 0.0f, float((1 << kGainBits) - 1)));
}
float weightFromCode(int code) noexcept { return float(code + 1) / 16.0f; }
int bandCount(int length) noexcept { return bandOf(length - 1) + 1; }
int adaptShift(const BlockShape& shape) noexcept { return shape.channels * shape.length <= 64 ? 4 : 5; }
bool canSplit(int length) noexcept { return length >= 2 * kMinSegment && length % 2 == 0; }

/// Quantiser step per octave band relative to the gain, from the band's centre frequency.
std::array<float, kMaxBands> stepTable(int length, int sampleRate_hz, float baseStep) noexcept {
  std::array<float, kMaxBands> steps{};
  const float binHz = 0.5f * float(sampleRate_hz) / float(length);
  for (int b = 0; b < bandCount(length); ++b) {
    const int lo = b == 0 ? 0 : 1 << (b - 1), hi = std::min(length, 1 << b) - 1;
    const float centre_hz = std::sqrt((float(lo) + 0.5f) * (float(hi) + 0.5f)) * binHz;
    steps[std::size_t(b)] = baseStep * std::pow(10.0f, kShapingStrength * vibrotactileThreshold_db(centre_hz) / 20.0f);
  }
  return steps;
}

/// What every segment of one block shares.
struct Block {
  std::span<const float> tables;
  float baseStep;
  const BlockShape& shape;
  CoderScratch s;
  int blockLength;
};

std::span<const float> tableFor(const Block& b, int length) noexcept {
  std::size_t offset = 0;
  for (int n = b.blockLength; n > length; n /= 2) offset += std::size_t(dctTableSize(n));
  return b.tables.subspan(offset, std::size_t(dctTableSize(length)));
}

/// What the coding of one segment length needs: its sample count, bands, steps, DCT table.
struct Segment {
  std::size_t n;
  int bands;
  std::array<float, kMaxBands> steps;
  std::span<const float> table;
};
Segment segmentOf(const Block& blk, int length) noexcept {
  return {std::size_t(length), bandCount(length), stepTable(length, blk.shape.sampleRate_hz, blk.baseStep),
          tableFor(blk, length)};
}

/// Encodes samples [offset, offset + length) of every channel; returns the squared error,
/// each channel's weighted by `weights` (1 / its rate-distortion slope) when given.
template <class Coder>
double encodeSegment(Coder& rc, Contexts& ctx, const Block& blk, const float* samples, int offset, int length,
                     int& previousGain, std::span<const double> weights) noexcept {
  const auto [n, bands, steps, table] = segmentOf(blk, length);
  const auto& shape = blk.shape;
  const CoderScratch& s = blk.s;
  double distortion = 0.0;
  bool previousActive = false;
  for (int c = 0; c < shape.channels; ++c) {
    const float* x = samples + std::size_t(c) * shape.stride + std::size_t(offset);
    const double weight = weights.empty() ? 1.0 : weights[std::size_t(c)];
    double energy = 0.0;
    for (std::size_t i = 0; i < n; ++i) {
      s.time[i] = std::isfinite(x[i]) ? std::clamp(x[i], -1.0f, 1.0f) : 0.0f;
      energy += double(s.time[i]) * s.time[i];
    }
    const float rms = float(std::sqrt(energy / double(n)));
    bool active = rms >= kSilentRms;
    if (active) {
      dctForward(table, s.time.first(n), s.coeff.first(n), s.work);
      int code = gainCode(rms);
      const float gain = gainFromCode(code);
      // One prediction weight for the channel (least squares), used in the bands where it helps.
      int weightCode = 0;
      std::array<float, kMaxBands> bandWeight{};
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
          const int lo = b == 0 ? 0 : 1 << (b - 1), hi = std::min(length, 1 << b);
          double plain = 0.0, residual = 0.0;
          for (int k = lo; k < hi; ++k) {
            const double v = s.coeff[std::size_t(k)], r = v - w * s.previous[std::size_t(k)];
            plain += v * v;
            residual += r * r;
          }
          if (residual < plain) bandWeight[std::size_t(b)] = w;
          before += plain;
          after += std::min(plain, residual);
        }
        predicted = cross > 0.0 && after < kPredictGain * before;
        if (!predicted) bandWeight.fill(0.0f);
      }
      int end = 0;
      double error = 0.0;
      for (std::size_t k = 0; k < n; ++k) {
        const int b = bandOf(int(k));
        const float prediction = bandWeight[std::size_t(b)] * s.previous[k];
        const float step = gain * steps[std::size_t(b)];
        const float r = s.coeff[k] - prediction;
        const int mag = int(std::min(std::floor(std::fabs(r) / step + 0.5f - kDeadzone), float(1 << kMaxEgPrefix)));
        s.q[k] = r < 0.0f ? -mag : mag;
        s.current[k] = prediction + float(s.q[k]) * step;
        error += double(s.coeff[k] - s.current[k]) * double(s.coeff[k] - s.current[k]);
        if (mag != 0) end = int(k) + 1;
      }
      active = predicted || end != 0;
      if (active) {
        codeBit(rc, ctx.active, active);
        codeGain(rc, ctx, code, previousGain);
        previousGain = code;
        if (previousActive) {
          codeBit(rc, ctx.predicted, predicted);
          if (predicted) {
            codeTree(rc, ctx.weight, weightCode, kWeightBits);
            for (int b = 0; b < bands; ++b) {
              bool on = bandWeight[std::size_t(b)] != 0.0f;
              codeBit(rc, ctx.bandPredicted[std::size_t(b)], on);
            }
          }
        }
        codeLength(rc, ctx, end, length);
        codeCoefficients(rc, ctx, s.q.first(n), end, length);
        std::copy_n(s.current.begin(), n, s.previous.begin());
        distortion += weight * error;
      }
    }
    if (!active) {
      codeBit(rc, ctx.active, active);
      std::fill_n(s.previous.begin(), n, 0.0f);
      distortion += weight * energy;
    }
    previousActive = active;
  }
  return distortion;
}

void decodeSegment(RangeDecoder& rc, Contexts& ctx, const Block& blk, float* samples, int offset, int length,
                   int& previousGain) noexcept {
  const auto [n, bands, steps, table] = segmentOf(blk, length);
  const auto& shape = blk.shape;
  const CoderScratch& s = blk.s;
  bool previousActive = false;
  for (int c = 0; c < shape.channels; ++c) {
    float* x = samples + std::size_t(c) * shape.stride + std::size_t(offset);
    bool active = false;
    codeBit(rc, ctx.active, active);
    if (!active) {
      std::fill_n(x, n, 0.0f);
      std::fill_n(s.previous.begin(), n, 0.0f);
      previousActive = false;
      continue;
    }
    int code = 0;
    codeGain(rc, ctx, code, previousGain);
    previousGain = code;
    const float gain = gainFromCode(code);
    std::array<float, kMaxBands> bandWeight{};
    bool predicted = false;
    if (previousActive) codeBit(rc, ctx.predicted, predicted);
    if (predicted) {
      int weightCode = 0;
      codeTree(rc, ctx.weight, weightCode, kWeightBits);
      for (int b = 0; b < bands; ++b) {
        bool on = false;
        codeBit(rc, ctx.bandPredicted[std::size_t(b)], on);
        if (on) bandWeight[std::size_t(b)] = weightFromCode(weightCode);
      }
    }
    int end = 0;
    codeLength(rc, ctx, end, length);
    end = std::min(end, length);
    std::fill_n(s.q.begin(), n, 0);
    codeCoefficients(rc, ctx, s.q.first(n), end, length);
    int nonzeroEnd = 0;
    for (std::size_t k = 0; k < n; ++k) {
      const int b = bandOf(int(k));
      s.current[k] = bandWeight[std::size_t(b)] * s.previous[k] + float(s.q[k]) * gain * steps[std::size_t(b)];
      if (s.current[k] != 0.0f) nonzeroEnd = int(k) + 1;
    }
    dctInverse(table, s.current.first(n), nonzeroEnd, std::span(x, n), s.work);
    for (std::size_t i = 0; i < n; ++i) x[i] = std::isfinite(x[i]) ? std::clamp(x[i], -1.0f, 1.0f) : 0.0f;
    std::copy_n(s.current.begin(), n, s.previous.begin());
    previousActive = true;
  }
}

bool splittable(int length, int depth) noexcept { return canSplit(length) && depth + 1 < kMaxSplitDepth; }

/// Rate-distortion cost of coding [offset, offset + length) best; appends the split flags that
/// reach it (pre-order, one per splittable node) to `splits`. Choices are priced with fresh contexts.
double chooseSegments(const Block& blk, const float* samples, int offset, int length, int depth,
                      std::span<const double> weights, std::span<std::uint8_t> splits, int& count) noexcept {
  Contexts fresh;
  BitCounter counter(adaptShift(blk.shape));
  int gain = -1;
  const double distortion = encodeSegment(counter, fresh, blk, samples, offset, length, gain, weights);
  const double wholeCost = counter.bits() + distortion;
  if (!splittable(length, depth)) return wholeCost;
  const int at = count++;
  splits[std::size_t(at)] = 0;
  const int mark = count;
  const double halves = chooseSegments(blk, samples, offset, length / 2, depth + 1, weights, splits, count) +
                        chooseSegments(blk, samples, offset + length / 2, length / 2, depth + 1, weights, splits, count);
  if (halves < wholeCost) {
    splits[std::size_t(at)] = 1;
    return halves;
  }
  count = mark;  // the halves' flags are not sent
  return wholeCost;
}

template <class Coder>
void codeSplits(Coder& rc, Contexts& ctx, int length, int depth, std::span<std::uint8_t> splits, int& index) noexcept {
  if (!splittable(length, depth)) return;
  bool split = splits[std::size_t(index)] != 0;
  codeBit(rc, ctx.split[std::size_t(depth)], split);
  splits[std::size_t(index++)] = split;
  if (!split) return;
  codeSplits(rc, ctx, length / 2, depth + 1, splits, index);
  codeSplits(rc, ctx, length / 2, depth + 1, splits, index);
}

/// Visits the leaves of a split tree (pre-order flags) in time order.
template <class Visit>
void forEachSegment(int offset, int length, int depth, std::span<const std::uint8_t> splits, int& index, Visit&& visit) {
  if (!splittable(length, depth) || splits[std::size_t(index++)] == 0) {
    visit(offset, length);
    return;
  }
  forEachSegment(offset, length / 2, depth + 1, splits, index, visit);
  forEachSegment(offset + length / 2, length / 2, depth + 1, splits, index, visit);
}

/// Chooses the segmentation and codes the block through `rc`.
template <class Coder>
void encodeBlock(Coder& rc, Contexts& ctx, const Block& blk, const float* samples) noexcept {
  const BlockShape& shape = blk.shape;
  std::array<std::uint8_t, kMaxSegmentNodes> splits{};
  int count = 0;
  if (canSplit(shape.length)) {
    // Distortion priced per channel at the quantiser step its whole-block level asks for, so
    // every candidate segmentation is judged on one scale.
    std::array<double, kMaxActuators> weights{};
    for (int c = 0; c < shape.channels; ++c) {
      double energy = 0.0;
      for (int i = 0; i < shape.length; ++i) {
        const float v = samples[std::size_t(c) * shape.stride + std::size_t(i)];
        energy += std::isfinite(v) ? double(v) * v : 0.0;
      }
      const double step = std::max(1e-4, std::sqrt(energy / shape.length)) * blk.baseStep;
      weights[std::size_t(c)] = 1.0 / (kLambdaPerStep2 * step * step);
    }
    chooseSegments(blk, samples, 0, shape.length, 0, std::span(weights).first(std::size_t(shape.channels)), splits, count);
  }
  int index = 0;
  codeSplits(rc, ctx, shape.length, 0, splits, index);
  index = 0;
  int gain = -1;
  forEachSegment(0, shape.length, 0, splits, index, [&](int offset, int length) {
    encodeSegment(rc, ctx, blk, samples, offset, length, gain, {});
  });
}

/// Adds every model's coded bits to counts[model] (Contexts::forEachModel order) and adapts
/// as the encoder does.
class ContextCounter {
 public:
  static constexpr bool kEncodes = true;
  ContextCounter(Contexts& ctx, int adaptShift, ContextCounts counts) noexcept
      : m_ctx(ctx), m_shift(adaptShift), m_counts(counts) {}
  void bit(BitModel& model, int bit) noexcept {
    std::size_t i = 0, found = 0;
    m_ctx.forEachModel([&](BitModel& m) {
      if (&m == &model) found = i;
      ++i;
    });
    m_counts[found][std::size_t(bit)] += 1.0;
    adapt(model, bit, m_shift);
  }
  void direct(int) noexcept {}

 private:
  Contexts& m_ctx;
  int m_shift;
  ContextCounts m_counts;
};

}  // namespace

std::size_t segmentTablesSize(int length) noexcept {
  std::size_t size = std::size_t(dctTableSize(length));
  for (int n = length; canSplit(n); n /= 2) size += std::size_t(dctTableSize(n / 2));
  return size;
}

void makeSegmentTables(int length, std::span<float> tables) noexcept {
  std::size_t offset = 0;
  for (int n = length;; n /= 2) {
    makeDctTable(n, tables.subspan(offset, std::size_t(dctTableSize(n))));
    offset += std::size_t(dctTableSize(n));
    if (!canSplit(n)) break;
  }
}

float perceptualBaseStep(int quality) noexcept {
  // quality 0..100 -> target noise 6..46 dB below the block level before shaping.
  return std::sqrt(12.0f) * std::pow(10.0f, -(6.0f + 0.4f * float(quality)) / 20.0f);
}

std::size_t encodePerceptual(std::span<const float> tables, float baseStep, const BlockShape& shape,
                             const float* samples, CoderScratch scratch, std::span<std::uint8_t> out,
                             bool& overflow) noexcept {
  const Block blk{tables, baseStep, shape, scratch, shape.length};
  Contexts ctx;
  RangeEncoder rc(out, adaptShift(shape));
  encodeBlock(rc, ctx, blk, samples);
  const std::size_t size = rc.finish();
  overflow = size == 0 && rc.overflowed();
  return size;
}

void countContextUse(std::span<const float> tables, float baseStep, const BlockShape& shape, const float* samples,
                     CoderScratch scratch, ContextCounts counts) noexcept {
  const Block blk{tables, baseStep, shape, scratch, shape.length};
  Contexts ctx;
  ContextCounter rc(ctx, adaptShift(shape), counts);
  encodeBlock(rc, ctx, blk, samples);
}

void decodePerceptual(std::span<const float> tables, float baseStep, const BlockShape& shape,
                      std::span<const std::uint8_t> in, CoderScratch scratch, float* samples) noexcept {
  const Block blk{tables, baseStep, shape, scratch, shape.length};
  Contexts ctx;
  RangeDecoder rc(in, adaptShift(shape));
  std::array<std::uint8_t, kMaxSegmentNodes> splits{};
  int index = 0;
  codeSplits(rc, ctx, shape.length, 0, splits, index);
  index = 0;
  int gain = -1;
  forEachSegment(0, shape.length, 0, splits, index, [&](int offset, int length) {
    decodeSegment(rc, ctx, blk, samples, offset, length, gain);
  });
}

}  // namespace vt::haptics::codec
