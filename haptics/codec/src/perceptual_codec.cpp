// The perceptual codec as a per-frame TactileCodec: one frame = one block of the perceptual
// block coder (perceptual_coder.cpp), with the DCT tables of every frame length made once.
#include <array>

#include "codec_internal.hpp"
#include "dct.hpp"
#include "perceptual_coder.hpp"

namespace vt::haptics::codec {

namespace {

using FrameTables = std::array<std::array<float, dctTableSize(kMaxBlockSamples)>, kMaxBlockSamples + 1>;

const FrameTables& frameTables() noexcept {
  static const FrameTables tables = [] {
    FrameTables t{};
    for (int n = 1; n <= kMaxBlockSamples; ++n) makeDctTable(n, t[std::size_t(n)]);
    return t;
  }();
  return tables;
}

struct FrameScratch {
  std::array<float, kMaxBlockSamples> coeff{}, previous{}, current{}, time{};
  std::array<float, 2 * kMaxBlockSamples> work{};
  std::array<int, kMaxBlockSamples> q{};
  CoderScratch view() noexcept { return {coeff, previous, current, time, work, q}; }
};

class PerceptualCodec final : public TactileCodec {
 public:
  explicit PerceptualCodec(int quality) noexcept : m_baseStep(perceptualBaseStep(quality)) { frameTables(); }

  CodecId id() const noexcept override { return CodecId::Perceptual; }

  std::size_t encode(const WaveBlock& block, const BlockFormat& f, std::span<std::uint8_t> out) const noexcept override {
    if (!validFormat(f)) return 0;
    FrameScratch scratch;
    bool overflow = false;
    return encodePerceptual(table(f), m_baseStep, shape(f), block[0].data(), scratch.view(), out, overflow);
  }

  bool decode(std::span<const std::uint8_t> data, const BlockFormat& f, WaveBlock& block) const noexcept override {
    block = {};
    if (!validFormat(f)) return false;
    FrameScratch scratch;
    decodePerceptual(table(f), m_baseStep, shape(f), data, scratch.view(), block[0].data());
    return true;
  }

 private:
  static bool validFormat(const BlockFormat& f) noexcept {
    return f.channels >= 1 && f.channels <= kMaxActuators && f.length >= 1 && f.length <= kMaxBlockSamples &&
           f.sampleRate_hz >= 1 && f.sampleRate_hz <= 96000;
  }
  static BlockShape shape(const BlockFormat& f) noexcept {
    return {f.channels, f.length, f.sampleRate_hz, kMaxBlockSamples};
  }
  static std::span<const float> table(const BlockFormat& f) noexcept {
    return std::span(frameTables()[std::size_t(f.length)]).first(std::size_t(dctTableSize(f.length)));
  }

  float m_baseStep;
};

}  // namespace

std::unique_ptr<TactileCodec> makePerceptual(int quality) { return std::make_unique<PerceptualCodec>(quality); }

}  // namespace vt::haptics::codec
