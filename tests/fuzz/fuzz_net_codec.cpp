// Tactile codec decoders on untrusted packet data: byte 0 = codec (value % 3) and block length
// ((value / 3) % 7: 0 = one frame through TactileCodec, 1..6 = kCodecBlockLengths_ms through a
// BlockDecoder), 1 = channels, 2 = frame length, the rest = the packet. Outputs must stay
// finite and within -1..1.
#include <cmath>
#include <cstdint>
#include <map>
#include <memory>
#include <span>
#include <tuple>

#include "vt/haptics/codec/codec.hpp"
#include "vt/haptics/codec/stream_codec.hpp"

namespace {

using namespace vt::haptics;

void checkBounded(const WaveBlock& block) {
  for (const auto& channel : block)
    for (float v : channel)
      if (!std::isfinite(v) || v < -1.0f || v > 1.0f) __builtin_trap();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const std::unique_ptr<TactileCodec> codecs[] = {
      makeCodec(CodecId::RawFloat32), makeCodec(CodecId::Pcm16), makeCodec(CodecId::Perceptual, 50)};
  static std::map<std::tuple<int, int, int, int>, std::unique_ptr<BlockDecoder>> decoders;
  if (size < 3) return 0;
  const int codec = data[0] % 3, blockIndex = (data[0] / 3) % 7;
  const std::span<const std::uint8_t> packet(data + 3, size - 3);
  if (blockIndex == 0) {
    const BlockFormat format{data[1] % (kMaxActuators + 2), data[2] % (kMaxBlockSamples + 2), 8000};
    WaveBlock block{};
    if (codecs[codec]->decode(packet, format, block)) checkBounded(block);
    return 0;
  }
  CodecConfig config;
  config.id = CodecId(codec + 1);
  config.channels = data[1] % kMaxActuators + 1;
  config.frameLength = data[2] % kMaxBlockSamples + 1;
  config.block_ms = kCodecBlockLengths_ms[std::size_t(blockIndex - 1)];
  if (!checkCodecConfig(config).empty()) return 0;
  auto& decoder = decoders[{codec, config.channels, config.frameLength, config.block_ms}];
  if (!decoder) decoder = makeBlockDecoder(config);
  if (decoder->decode(packet))
    for (int i = 0; i < decoder->frameCount(); ++i) checkBounded(decoder->frame(i));
  return 0;
}
