// The two lossless-ish baselines: float32 as is, and 16-bit PCM (what the ratio goal compares to).
#include <algorithm>
#include <bit>
#include <cmath>

#include "codec_internal.hpp"
#include "vt/haptics/wav.hpp"

namespace vt::haptics::codec {

namespace {

bool validFormat(const BlockFormat& f) noexcept {
  return f.channels >= 1 && f.channels <= kMaxActuators && f.length >= 1 && f.length <= kMaxBlockSamples;
}

float sanitize(float v) noexcept { return std::isfinite(v) ? std::clamp(v, -1.0f, 1.0f) : 0.0f; }

class RawFloat32Codec final : public TactileCodec {
 public:
  CodecId id() const noexcept override { return CodecId::RawFloat32; }
  std::size_t encode(const WaveBlock& block, const BlockFormat& f, std::span<std::uint8_t> out) const noexcept override {
    const std::size_t size = std::size_t(f.channels) * std::size_t(f.length) * 4;
    if (!validFormat(f) || out.size() < size) return 0;
    std::size_t pos = 0;
    for (int c = 0; c < f.channels; ++c)
      for (int i = 0; i < f.length; ++i) {
        const auto bits = std::bit_cast<std::uint32_t>(block[std::size_t(c)][std::size_t(i)]);
        for (int b = 0; b < 4; ++b) out[pos++] = std::uint8_t(bits >> (8 * b));
      }
    return size;
  }
  bool decode(std::span<const std::uint8_t> data, const BlockFormat& f, WaveBlock& block) const noexcept override {
    block = {};
    if (!validFormat(f) || data.size() != std::size_t(f.channels) * std::size_t(f.length) * 4) return false;
    std::size_t pos = 0;
    for (int c = 0; c < f.channels; ++c)
      for (int i = 0; i < f.length; ++i) {
        std::uint32_t bits = 0;
        for (int b = 0; b < 4; ++b) bits |= std::uint32_t(data[pos++]) << (8 * b);
        block[std::size_t(c)][std::size_t(i)] = sanitize(std::bit_cast<float>(bits));
      }
    return true;
  }
};

class Pcm16Codec final : public TactileCodec {
 public:
  CodecId id() const noexcept override { return CodecId::Pcm16; }
  std::size_t encode(const WaveBlock& block, const BlockFormat& f, std::span<std::uint8_t> out) const noexcept override {
    const std::size_t size = std::size_t(f.channels) * std::size_t(f.length) * 2;
    if (!validFormat(f) || out.size() < size) return 0;
    std::size_t pos = 0;
    for (int c = 0; c < f.channels; ++c)
      for (int i = 0; i < f.length; ++i) {
        const float v = sanitize(block[std::size_t(c)][std::size_t(i)]);
        const auto q = std::uint16_t(std::int16_t(std::lround(v * 32767.0f)));
        out[pos++] = std::uint8_t(q);
        out[pos++] = std::uint8_t(q >> 8);
      }
    return size;
  }
  bool decode(std::span<const std::uint8_t> data, const BlockFormat& f, WaveBlock& block) const noexcept override {
    block = {};
    if (!validFormat(f) || data.size() != std::size_t(f.channels) * std::size_t(f.length) * 2) return false;
    std::size_t pos = 0;
    for (int c = 0; c < f.channels; ++c)
      for (int i = 0; i < f.length; ++i, pos += 2) {
        const auto q = std::int16_t(std::uint16_t(data[pos] | (data[pos + 1] << 8)));
        block[std::size_t(c)][std::size_t(i)] = wavSampleValue(q);
      }
    return true;
  }
};

}  // namespace

std::unique_ptr<TactileCodec> makeRawFloat32() { return std::make_unique<RawFloat32Codec>(); }
std::unique_ptr<TactileCodec> makePcm16() { return std::make_unique<Pcm16Codec>(); }

}  // namespace vt::haptics::codec
