// Tactile codec decoders on untrusted packet data: byte 0 = codec, 1 = channels, 2 = block
// length, the rest = the encoded block. Outputs must stay finite and within -1..1.
#include <cmath>
#include <cstdint>
#include <memory>
#include <span>

#include "vt/haptics/codec/codec.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace vt::haptics;
  static const std::unique_ptr<TactileCodec> codecs[] = {
      makeCodec(CodecId::RawFloat32), makeCodec(CodecId::Pcm16), makeCodec(CodecId::Perceptual, 50)};
  if (size < 3) return 0;
  const TactileCodec& codec = *codecs[data[0] % 3];
  const BlockFormat format{data[1] % (kMaxActuators + 2), data[2] % (kMaxBlockSamples + 2), 8000};
  WaveBlock block{};
  if (codec.decode(std::span(data + 3, size - 3), format, block)) {
    for (const auto& channel : block)
      for (float v : channel)
        if (!std::isfinite(v) || v < -1.0f || v > 1.0f) __builtin_trap();
  }
  return 0;
}
