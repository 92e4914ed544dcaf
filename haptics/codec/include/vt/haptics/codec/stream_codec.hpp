#pragma once
// Tactile stream codec with a block length setting (API stable; format in docs/protocol.md).
//
// A codec block is block_ms of waveform: framesPerBlock(config) consecutive ActuatorFrame
// blocks of frameLength samples per channel. The encoder buffers that many frames and emits
// one packet; the decoder turns one packet back into that many frames. Both sides build
// their instance from the same CodecConfig (the session's hello/accept carries it).
//
//   CodecConfig config;                       // perceptual, quality 50, 4 ms, 1 channel, 8 kHz
//   config.channels = 5;
//   config.block_ms = 16;
//   auto encoder = makeBlockEncoder(config);  // setup thread; throws vt::Error on a bad config
//   auto decoder = makeBlockDecoder(config);
//   // sender, one thread, every frame in order:
//   if (encoder->push(frame.block)) send(encoder->packet());
//   // receiver, one thread, every packet:
//   if (decoder->decode(bytes))
//     for (int i = 0; i < decoder->frameCount(); ++i) play(decoder->frame(i));
//
// Packets are self-contained (a lost packet costs one block, the next decodes). Within a
// packet the perceptual codec transforms the whole block per channel, carries its
// entropy-coder contexts across channels and predicts each channel from the one before
// (actuators on a glove are correlated). At block_ms = 4 and frameLength 32 a perceptual
// packet is byte for byte what TactileCodec::encode (codec.hpp) produces for that frame.
//
// Threads: creation allocates (setup thread); push/packet/flush/reset and decode/frame are
// noexcept and allocation-free, for one thread at a time per instance.
#include <array>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <span>
#include <string_view>

#include "vt/haptics/codec/codec.hpp"

namespace vt::haptics {

/// Block lengths a stream may use; 4 ms (one frame at 8 kHz) is the default for live touch.
inline constexpr std::array<int, 6> kCodecBlockLengths_ms = {4, 8, 16, 32, 64, 128};
/// Most samples per channel in one codec block (128 ms at 32 kHz).
inline constexpr int kMaxCodecBlockSamples = 4096;

/// Creation parameters of a stream encoder/decoder pair (both sides use the same values).
struct CodecConfig {
  CodecId id = CodecId::Perceptual;
  int quality = 50;                   // 0..100, lossy codecs only: higher = more bits, less noise
  int channels = 1;                   // actuators, 1..kMaxActuators
  int sampleRate_hz = 8000;           // 1..96000
  int frameLength = kMaxBlockSamples; // samples per channel in one ActuatorFrame, 1..kMaxBlockSamples
  int block_ms = 4;                   // one of kCodecBlockLengths_ms
};

/// Empty when `config` is usable, else a one-line reason naming the field (for untrusted
/// offers: never throws). block_ms must hold a whole number of frames, at most
/// kMaxCodecBlockSamples samples per channel.
std::string_view checkCodecConfig(const CodecConfig& config) noexcept;
/// Frames in one codec block (block_ms * sampleRate_hz / 1000 / frameLength); 0 when invalid.
int framesPerBlock(const CodecConfig& config) noexcept;
/// Largest packet an encoder of `config` emits (raw/PCM: exactly this; perceptual: 4 bytes a
/// sample, far above what it needs); 0 when invalid.
std::size_t maxPacketBytes(const CodecConfig& config) noexcept;

/// Buffers frames and emits one packet per codec block.
class BlockEncoder {
 public:
  virtual ~BlockEncoder() = default;
  /// Appends one frame (the first channels x frameLength samples are read). True when that
  /// completed a block: packet() then holds it until the next push/flush/reset.
  virtual bool push(const WaveBlock& frame) noexcept = 0;
  /// Pads a partial block with silence and encodes it (end of a recording); false when no
  /// frame was pending.
  virtual bool flush() noexcept = 0;
  /// Drops pending frames and the last packet (a new session or stream).
  virtual void reset() noexcept = 0;
  /// The last completed packet (empty after reset). A perceptual block of silence may be empty.
  virtual std::span<const std::uint8_t> packet() const noexcept = 0;
  /// Frames pushed since the last packet.
  virtual int pending() const noexcept = 0;
  /// The configuration it was made with.
  virtual const CodecConfig& config() const noexcept = 0;
};

/// Decodes packets into frames.
class BlockDecoder {
 public:
  virtual ~BlockDecoder() = default;
  /// Decodes one packet; false when it cannot be a block of this config (frames are then
  /// silent). Work is bounded by the config whatever the bytes; outputs are finite, in -1..1.
  virtual bool decode(std::span<const std::uint8_t> packet) noexcept = 0;
  /// Frames per packet (framesPerBlock of the config).
  virtual int frameCount() const noexcept = 0;
  /// Frame i (0 = oldest) of the last decode; samples beyond channels x frameLength are zero.
  virtual const WaveBlock& frame(int i) const noexcept = 0;
  /// The configuration it was made with.
  virtual const CodecConfig& config() const noexcept = 0;
};

/// Creates an encoder; throws vt::Error naming the field when checkCodecConfig refuses.
std::unique_ptr<BlockEncoder> makeBlockEncoder(const CodecConfig& config);
/// Creates a decoder; throws vt::Error naming the field when checkCodecConfig refuses.
std::unique_ptr<BlockDecoder> makeBlockDecoder(const CodecConfig& config);

}  // namespace vt::haptics
