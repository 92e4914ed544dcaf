#pragma once
// The perceptual coder's bit-stream syntax, one routine per element for both directions: the
// encoder (RangeEncoder, or BitCounter to estimate) passes the values to write, the decoder
// receives the values read, so the syntax lives in one place. Internal to perceptual_coder.cpp.
#include <algorithm>
#include <array>
#include <bit>
#include <cstdint>
#include <cstdlib>
#include <span>

#include "context_priors.hpp"
#include "range_coder.hpp"

namespace vt::haptics::codec::syntax {

inline constexpr int kGainBits = 4;
inline constexpr int kMaxEgPrefix = 16;
inline constexpr int kMaxBands = 14;        // octave bands of the coefficient index: bit_width(k) < 14
inline constexpr int kPositionClasses = 6;  // octaves of frequency relative to a 32-sample block
inline constexpr int kWidthBits = 4;        // most bits of the coded length's bit width (0..13)
inline constexpr int kWeightBits = 5;       // prediction weight (code + 1) / 16
inline constexpr int kMaxSplitDepth = 8;

/// Adaptive models; one set per packet, carried across its segments and channels. Every
/// packet starts them from the same fixed priors (context_priors.hpp), so it stands alone.
struct Contexts {
  std::array<BitModel, kMaxSplitDepth> split{};
  BitModel active;
  std::array<BitModel, 1 << kGainBits> gain{};
  BitModel gainSame;
  std::array<BitModel, 1 << kGainBits> gainDelta{};
  BitModel predicted;
  std::array<BitModel, 1 << kWeightBits> weight{};
  std::array<BitModel, kMaxBands> bandPredicted{};
  std::array<BitModel, 1 << kWidthBits> width{};
  std::array<std::array<BitModel, 4>, kPositionClasses> significant{};
  std::array<std::array<BitModel, 3>, kPositionClasses> greater1{};
  std::array<BitModel, kPositionClasses> greater2{};
  std::array<BitModel, kMaxEgPrefix + 1> egPrefix{};

  /// Calls visit(model) for every model, always in the same order (the priors' order).
  template <class Visit>
  void forEachModel(Visit&& visit) {
    for (auto& m : split) visit(m);
    visit(active);
    for (auto& m : gain) visit(m);
    visit(gainSame);
    for (auto& m : gainDelta) visit(m);
    visit(predicted);
    for (auto& m : weight) visit(m);
    for (auto& m : bandPredicted) visit(m);
    for (auto& m : width) visit(m);
    for (auto& row : significant)
      for (auto& m : row) visit(m);
    for (auto& row : greater1)
      for (auto& m : row) visit(m);
    for (auto& m : greater2) visit(m);
    for (auto& m : egPrefix) visit(m);
  }
  Contexts() noexcept {
    std::size_t i = 0;
    forEachModel([&](BitModel& m) { m.p = kContextPriors[i++]; });
  }
};
static_assert(sizeof(Contexts) == kContextModels * sizeof(BitModel), "context_priors.hpp: one prior per model");

inline int bandOf(int k) noexcept { return std::bit_width(unsigned(k)); }

/// One binary decision (flag) through `model`.
template <class Coder>
void codeBit(Coder& rc, BitModel& model, bool& value) noexcept {
  if constexpr (Coder::kEncodes) rc.bit(model, value);
  else value = rc.bit(model) != 0;
}

/// An unsigned value of `bits` bits through a binary tree of models.
template <class Coder>
void codeTree(Coder& rc, std::span<BitModel> tree, int& value, int bits) noexcept {
  int node = 1;
  for (int i = bits - 1; i >= 0; --i) {
    int bit = (value >> i) & 1;
    if constexpr (Coder::kEncodes) rc.bit(tree[std::size_t(node)], bit);
    else bit = rc.bit(tree[std::size_t(node)]);
    node = (node << 1) | bit;
  }
  value = node - (1 << bits);
}

/// `bits` equiprobable bits, most significant first.
template <class Coder>
void codeRaw(Coder& rc, unsigned& value, int bits) noexcept {
  for (int j = bits - 1; j >= 0; --j) {
    if constexpr (Coder::kEncodes) rc.direct(int((value >> j) & 1u));
    else value = (value << 1) | unsigned(rc.direct());
  }
}

/// The gain: a bit tree for the first active channel, then the difference to the previous
/// active channel's (sign raw, magnitude in adaptive unary): the fingers of a slide share levels.
template <class Coder>
void codeGain(Coder& rc, Contexts& ctx, int& code, int previousCode) noexcept {
  if (previousCode < 0) {
    codeTree(rc, ctx.gain, code, kGainBits);
    return;
  }
  const int delta = code - previousCode;
  bool same = delta == 0;
  codeBit(rc, ctx.gainSame, same);
  if (same) {
    code = previousCode;
    return;
  }
  unsigned negative = Coder::kEncodes && delta < 0;  // codeRaw shifts the decoded bits into 0
  codeRaw(rc, negative, 1);
  const int limit = negative ? previousCode : (1 << kGainBits) - 1 - previousCode;
  int magnitude = 1;
  for (;; ++magnitude) {
    if (magnitude >= limit) break;
    bool more = magnitude < std::abs(delta);
    codeBit(rc, ctx.gainDelta[std::size_t(magnitude)], more);
    if (!more) break;
  }
  code = std::clamp(previousCode + (negative ? -magnitude : magnitude), 0, (1 << kGainBits) - 1);
}

/// The number of coefficients up to the last nonzero one: bit width (tree), then the bits below
/// the leading one (raw).
template <class Coder>
void codeLength(Coder& rc, Contexts& ctx, int& end, int length) noexcept {
  int width = std::bit_width(unsigned(end));
  // As few tree levels as the segment's longest width needs (3 for 32 samples).
  codeTree(rc, ctx.width, width, std::bit_width(unsigned(std::bit_width(unsigned(length)))));
  unsigned value = width == 0 ? 0u : (Coder::kEncodes ? unsigned(end) : 1u);
  if (width > 1) codeRaw(rc, value, width - 1);
  end = int(value);
}

inline int positionClass(int k, int length) noexcept {
  return std::min(kPositionClasses - 1, bandOf(int(std::int64_t(k) * 32 / length)));
}
inline int neighbourhood(std::span<const int> q, int k) noexcept {
  const int a = k >= 1 ? std::min(2, std::abs(q[std::size_t(k - 1)])) : 0;
  const int b = k >= 2 ? std::min(1, std::abs(q[std::size_t(k - 2)])) : 0;
  return a + b;
}

/// Quantised coefficients q[0..end): significance (context: frequency class, neighbours; the
/// last one is nonzero by definition), raw sign, > 1 and > 2 flags, Exp-Golomb remainder.
template <class Coder>
void codeCoefficients(Coder& rc, Contexts& ctx, std::span<int> q, int end, int length) noexcept {
  for (int k = 0; k < end; ++k) {
    const int pc = positionClass(k, length), nb = neighbourhood(q, k);
    int mag = std::abs(q[std::size_t(k)]);
    bool significant = mag != 0 || k + 1 == end;
    if (k + 1 < end) codeBit(rc, ctx.significant[std::size_t(pc)][std::size_t(nb)], significant);
    if (!significant) {
      q[std::size_t(k)] = 0;
      continue;
    }
    unsigned negative = Coder::kEncodes && q[std::size_t(k)] < 0;
    codeRaw(rc, negative, 1);
    bool more = mag > 1;
    codeBit(rc, ctx.greater1[std::size_t(pc)][std::size_t(std::min(nb, 2))], more);
    if (!more) {
      mag = 1;
    } else {
      bool more2 = mag > 2;
      codeBit(rc, ctx.greater2[std::size_t(pc)], more2);
      if (!more2) {
        mag = 2;
      } else {
        // Exp-Golomb of mag - 3: prefix length (adaptive unary), then that many raw bits.
        unsigned rest = Coder::kEncodes ? unsigned(mag - 3) + 1 : 1u;
        const int bits = Coder::kEncodes ? std::bit_width(rest) - 1 : 0;
        int prefix = 0;
        for (;; ++prefix) {
          if (prefix >= kMaxEgPrefix) break;
          bool longer = prefix < bits;
          codeBit(rc, ctx.egPrefix[std::size_t(prefix)], longer);
          if (!longer) break;
        }
        codeRaw(rc, rest, prefix);
        mag = int(rest - 1) + 3;
      }
    }
    q[std::size_t(k)] = negative ? -mag : mag;
  }
}

}  // namespace vt::haptics::codec::syntax
