// Block encoders/decoders over several frames: the perceptual codec codes the whole block at
// once (perceptual_coder.cpp); raw float32 and 16-bit PCM concatenate their per-frame blocks.
#include "vt/haptics/codec/stream_codec.hpp"

#include <algorithm>
#include <optional>
#include <vector>

#include "perceptual_coder.hpp"
#include "vt/core/error.hpp"

namespace vt::haptics {

namespace {

int blockSamples(const CodecConfig& c) noexcept { return int(std::int64_t(c.block_ms) * c.sampleRate_hz / 1000); }

/// Bytes of one frame for the codecs that code frame by frame (raw float32, 16-bit PCM).
std::size_t frameBytes(const CodecConfig& c) noexcept {
  return std::size_t(c.channels) * std::size_t(c.frameLength) * (c.id == CodecId::Pcm16 ? 2 : 4);
}

void checkOrThrow(const CodecConfig& config) {
  const std::string_view why = checkCodecConfig(config);
  if (!why.empty()) fail("tactile codec: ", why);
}

/// Scratch and tables of the perceptual block coder for one block length (allocated once).
class PerceptualWork {
 public:
  explicit PerceptualWork(const CodecConfig& c)
      : m_length(std::size_t(blockSamples(c))),
        m_baseStep(codec::perceptualBaseStep(c.quality)),
        m_table(codec::segmentTablesSize(int(m_length))),
        m_floats(6 * m_length),
        m_q(m_length),
        m_samples(std::size_t(c.channels) * m_length),
        m_shape{c.channels, int(m_length), c.sampleRate_hz, m_length} {
    codec::makeSegmentTables(int(m_length), m_table);
  }
  codec::CoderScratch scratch() noexcept {
    const std::span<float> f(m_floats);
    return {f.subspan(0, m_length), f.subspan(m_length, m_length), f.subspan(2 * m_length, m_length),
            f.subspan(3 * m_length, m_length), f.subspan(4 * m_length, 2 * m_length), m_q};
  }
  std::size_t length() const noexcept { return m_length; }
  float* samples(int channel) noexcept { return m_samples.data() + std::size_t(channel) * m_length; }

  std::size_t encode(std::span<std::uint8_t> out, bool& overflow) noexcept {
    return codec::encodePerceptual(m_table, m_baseStep, m_shape, m_samples.data(), scratch(), out, overflow);
  }
  void decode(std::span<const std::uint8_t> in) noexcept {
    codec::decodePerceptual(m_table, m_baseStep, m_shape, in, scratch(), m_samples.data());
  }

 private:
  std::size_t m_length;
  float m_baseStep;
  std::vector<float> m_table, m_floats;
  std::vector<int> m_q;
  std::vector<float> m_samples;
  codec::BlockShape m_shape;
};

class Encoder final : public BlockEncoder {
 public:
  explicit Encoder(const CodecConfig& c)
      : m_config(c), m_frames(framesPerBlock(c)), m_packet(maxPacketBytes(c)) {
    if (c.id == CodecId::Perceptual) m_perceptual.emplace(c);
    else m_frameCodec = makeCodec(c.id, c.quality);
  }

  bool push(const WaveBlock& frame) noexcept override {
    if (m_pending == 0) m_size = 0;
    const auto offset = std::size_t(m_pending) * std::size_t(m_config.frameLength);
    if (m_perceptual) {
      for (int c = 0; c < m_config.channels; ++c)
        std::copy_n(frame[std::size_t(c)].begin(), m_config.frameLength, m_perceptual->samples(c) + offset);
    } else {
      const BlockFormat format{m_config.channels, m_config.frameLength, m_config.sampleRate_hz};
      const std::size_t bytes = frameBytes(m_config);
      m_frameCodec->encode(frame, format, std::span(m_packet).subspan(std::size_t(m_pending) * bytes, bytes));
    }
    if (++m_pending < m_frames) return false;
    finishBlock();
    return true;
  }

  bool flush() noexcept override {
    if (m_pending == 0) return false;
    const WaveBlock silence{};
    while (m_pending != 0) push(silence);
    return true;
  }

  void reset() noexcept override {
    m_pending = 0;
    m_size = 0;
  }

  std::span<const std::uint8_t> packet() const noexcept override { return std::span(m_packet).first(m_size); }
  int pending() const noexcept override { return m_pending; }
  const CodecConfig& config() const noexcept override { return m_config; }

 private:
  void finishBlock() noexcept {
    m_pending = 0;
    if (!m_perceptual) {
      m_size = std::size_t(m_frames) * frameBytes(m_config);
      return;
    }
    // maxPacketBytes is 32 bits a sample, far above what coded blocks take; a block that did
    // not fit would go out empty (silence) rather than cut.
    bool overflow = false;
    m_size = m_perceptual->encode(m_packet, overflow);
  }

  CodecConfig m_config;
  int m_frames;
  std::vector<std::uint8_t> m_packet;
  std::size_t m_size = 0;
  int m_pending = 0;
  std::optional<PerceptualWork> m_perceptual;
  std::unique_ptr<TactileCodec> m_frameCodec;
};

class Decoder final : public BlockDecoder {
 public:
  explicit Decoder(const CodecConfig& c) : m_config(c), m_frames(std::size_t(framesPerBlock(c))) {
    if (c.id == CodecId::Perceptual) m_perceptual.emplace(c);
    else m_frameCodec = makeCodec(c.id, c.quality);
  }

  bool decode(std::span<const std::uint8_t> packet) noexcept override {
    for (auto& f : m_frames) f = {};
    const auto length = std::size_t(m_config.frameLength);
    if (m_perceptual) {
      m_perceptual->decode(packet);
      for (std::size_t i = 0; i < m_frames.size(); ++i)
        for (int c = 0; c < m_config.channels; ++c)
          std::copy_n(m_perceptual->samples(c) + i * length, length, m_frames[i][std::size_t(c)].begin());
      return true;
    }
    const std::size_t bytes = frameBytes(m_config);
    if (packet.size() != m_frames.size() * bytes) return false;
    const BlockFormat format{m_config.channels, m_config.frameLength, m_config.sampleRate_hz};
    for (std::size_t i = 0; i < m_frames.size(); ++i) {
      if (!m_frameCodec->decode(packet.subspan(i * bytes, bytes), format, m_frames[i])) {
        for (auto& f : m_frames) f = {};
        return false;
      }
    }
    return true;
  }

  int frameCount() const noexcept override { return int(m_frames.size()); }
  const WaveBlock& frame(int i) const noexcept override { return m_frames[std::size_t(i)]; }
  const CodecConfig& config() const noexcept override { return m_config; }

 private:
  CodecConfig m_config;
  std::vector<WaveBlock> m_frames;
  std::optional<PerceptualWork> m_perceptual;
  std::unique_ptr<TactileCodec> m_frameCodec;
};

}  // namespace

std::string_view checkCodecConfig(const CodecConfig& c) noexcept {
  if (!isKnownCodec(std::uint8_t(c.id))) return "codec id is not a known codec";
  if (c.quality < 0 || c.quality > 100) return "quality is outside 0..100";
  if (c.channels < 1 || c.channels > kMaxActuators) return "channels is outside 1..10";
  if (c.sampleRate_hz < 1 || c.sampleRate_hz > 96000) return "sample rate is outside 1..96000 Hz";
  if (c.frameLength < 1 || c.frameLength > kMaxBlockSamples) return "frame length is outside 1..32 samples";
  if (std::find(kCodecBlockLengths_ms.begin(), kCodecBlockLengths_ms.end(), c.block_ms) == kCodecBlockLengths_ms.end())
    return "block length is not one of 4, 8, 16, 32, 64, 128 ms";
  const std::int64_t samples = std::int64_t(c.block_ms) * c.sampleRate_hz;
  if (samples % 1000 != 0 || (samples / 1000) % c.frameLength != 0 || samples / 1000 < c.frameLength)
    return "block length is not a whole number of frames at this sample rate and frame length";
  if (samples / 1000 > kMaxCodecBlockSamples) return "block length holds more than 4096 samples per channel";
  return {};
}

int framesPerBlock(const CodecConfig& c) noexcept {
  return checkCodecConfig(c).empty() ? blockSamples(c) / c.frameLength : 0;
}

std::size_t maxPacketBytes(const CodecConfig& c) noexcept {
  if (!checkCodecConfig(c).empty()) return 0;
  if (c.id != CodecId::Perceptual) return std::size_t(framesPerBlock(c)) * frameBytes(c);
  return std::size_t(c.channels) * std::size_t(blockSamples(c)) * 4;
}

std::unique_ptr<BlockEncoder> makeBlockEncoder(const CodecConfig& config) {
  checkOrThrow(config);
  return std::make_unique<Encoder>(config);
}

std::unique_ptr<BlockDecoder> makeBlockDecoder(const CodecConfig& config) {
  checkOrThrow(config);
  return std::make_unique<Decoder>(config);
}

}  // namespace vt::haptics
