#pragma once
// Tactile stream codecs, negotiated per session (docs/protocol.md): raw float32, 16-bit PCM,
// and a perceptual DCT codec. One codec block = one ActuatorFrame's waveform block (every
// channel = one actuator). Blocks are coded independently so a lost packet costs one block.
// Codecs are stateless: encode/decode are const, noexcept, allocation-free, any thread. Blocks
// of several frames (8..128 ms): stream_codec.hpp.
#include <array>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <span>
#include <string_view>

#include "vt/haptics/actuator_frame.hpp"

namespace vt::haptics {

/// Wire ids of the codecs (never reuse a number).
enum class CodecId : std::uint8_t { RawFloat32 = 1, Pcm16 = 2, Perceptual = 3 };

/// The waveform block of one frame: [actuator][sample], samples in -1..1.
using WaveBlock = std::array<std::array<float, kMaxBlockSamples>, kMaxActuators>;

/// Shape of one block on the wire (both sides know it from the session and the packet).
struct BlockFormat {
  int channels = 1;             // 1..kMaxActuators
  int length = kMaxBlockSamples;  // samples per channel, 1..kMaxBlockSamples
  int sampleRate_hz = 8000;
};

/// One codec; instances are immutable after creation.
class TactileCodec {
 public:
  virtual ~TactileCodec() = default;
  virtual CodecId id() const noexcept = 0;
  /// Encodes the first format.channels x format.length samples; returns the byte count,
  /// or 0 when `out` is too small or the format is out of range.
  virtual std::size_t encode(const WaveBlock& block, const BlockFormat& format,
                             std::span<std::uint8_t> out) const noexcept = 0;
  /// Decodes into `block` (samples beyond the format are zeroed, outputs clamped to -1..1);
  /// false when the data cannot be a block of this format (counted by the caller).
  virtual bool decode(std::span<const std::uint8_t> data, const BlockFormat& format,
                      WaveBlock& block) const noexcept = 0;
};

/// Largest encoded block of any codec (raw float32 of every actuator).
inline constexpr std::size_t kMaxEncodedBlock = std::size_t(kMaxActuators) * kMaxBlockSamples * 4;

/// Creates a codec. quality 0..100 matters only to lossy codecs (higher = more bits, less noise).
/// Throws vt::Error for an unknown id or quality.
std::unique_ptr<TactileCodec> makeCodec(CodecId id, int quality = 50);
/// True for the ids makeCodec knows (for negotiation of untrusted offers).
bool isKnownCodec(std::uint8_t id) noexcept;
/// "raw-f32", "pcm16", "perceptual".
std::string_view codecName(CodecId id) noexcept;
/// Parses a codecName; false when unknown.
bool parseCodecName(std::string_view name, CodecId& out) noexcept;

}  // namespace vt::haptics
