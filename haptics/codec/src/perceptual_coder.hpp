#pragma once
// The perceptual block coder shared by TactileCodec (one frame) and BlockEncoder/Decoder
// (a block of several frames): channels x length samples <-> one self-contained bit stream.
#include <array>
#include <cstddef>
#include <cstdint>
#include <span>

#include "vt/haptics/actuator_frame.hpp"

namespace vt::haptics::codec {

/// Samples of one block: channel c, sample i at samples[c * stride + i].
struct BlockShape {
  int channels = 1;
  int length = 1;
  int sampleRate_hz = 8000;
  std::size_t stride = 0;
};

/// Working memory of one call: each span holds at least `length` values, `work` twice that.
struct CoderScratch {
  std::span<float> coeff, previous, current, time, work;
  std::span<int> q;
};

/// Shortest segment the encoder cuts a block into (4 ms at 8 kHz).
inline constexpr int kMinSegment = 32;
/// Most splittable nodes of a block's segment tree (4096 samples down to 32).
inline constexpr int kMaxSegmentNodes = 128;

/// Floats of the DCT tables of a block length and of every segment length it can be cut into.
std::size_t segmentTablesSize(int length) noexcept;
/// Fills those tables (`tables` holds segmentTablesSize(length) floats).
void makeSegmentTables(int length, std::span<float> tables) noexcept;
/// Quantiser step (relative to the block gain) that quality 0..100 asks for.
float perceptualBaseStep(int quality) noexcept;
/// Encodes; returns the byte count (0 = every channel silent, or `out` too small: `overflow`).
std::size_t encodePerceptual(std::span<const float> tables, float baseStep, const BlockShape& shape,
                             const float* samples, CoderScratch scratch, std::span<std::uint8_t> out,
                             bool& overflow) noexcept;
/// Per context model (Contexts::forEachModel order): how many 0 and 1 bits a block codes.
using ContextCounts = std::span<std::array<double, 2>>;
/// Encodes without output, adding each model's coded bits to `counts` (to train the priors).
void countContextUse(std::span<const float> tables, float baseStep, const BlockShape& shape, const float* samples,
                     CoderScratch scratch, ContextCounts counts) noexcept;
/// Decodes into samples (clamped to -1..1). Any bytes decode to something bounded.
void decodePerceptual(std::span<const float> tables, float baseStep, const BlockShape& shape,
                      std::span<const std::uint8_t> in, CoderScratch scratch, float* samples) noexcept;

}  // namespace vt::haptics::codec
