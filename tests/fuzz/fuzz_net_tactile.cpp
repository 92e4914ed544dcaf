// The client's whole tactile path on an untrusted datagram: packet decoding, then the frames
// rebuilt through the session's block decoder (codec and block length chosen by the first
// byte) and the jitter buffer.
#include <cmath>
#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include "vt/net/jitter_buffer.hpp"
#include "vt/net/tactile_stream.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace vt::haptics;
  constexpr CodecId kCodecs[] = {CodecId::RawFloat32, CodecId::Pcm16, CodecId::Perceptual};
  static std::vector<std::unique_ptr<BlockDecoder>> decoders;  // [codec][block length][actuators - 1]
  if (decoders.empty())
    for (CodecId id : kCodecs)
      for (int block_ms : kCodecBlockLengths_ms)
        for (int channels = 1; channels <= kMaxActuators; ++channels)
          decoders.push_back(makeBlockDecoder({id, 50, channels, 8000, kMaxBlockSamples, block_ms}));
  if (size < 2) return 0;
  const int codec = data[0] % 3, length = (data[0] / 3) % 6, channels = 1 + data[1] % kMaxActuators;
  BlockDecoder& decoder = *decoders[std::size_t((codec * 6 + length) * kMaxActuators + channels - 1)];
  vt::net::StreamContext context;
  context.actuatorCount = channels;
  context.framesPerBlock = decoder.frameCount();
  vt::net::Packet packet;
  if (vt::net::decodeStream(std::span(data + 2, size - 2), context, packet) != vt::net::DecodeStatus::Ok) return 0;
  const auto* tactile = std::get_if<vt::net::Tactile>(&packet.message);
  if (!tactile) return 0;
  static std::array<ActuatorFrame, vt::net::kMaxFramesPerBlock> frames;
  bool any = false;
  for (int b = 0; b < tactile->blockCount; ++b) {
    if (!vt::net::unpackBlock(*tactile, b, decoder, tactile->frequency_hz, frames)) continue;
    any = true;
    for (int f = 0; f < decoder.frameCount(); ++f)
      for (const auto& channel : frames[std::size_t(f)].block)
        for (float v : channel)
          if (!std::isfinite(v) || v < -1.0f || v > 1.0f) __builtin_trap();
  }
  if (!any) return 0;
  static vt::net::JitterBuffer buffer({4'000'000});
  buffer = vt::net::JitterBuffer({4'000'000});
  ActuatorFrame frame = frames[0];
  buffer.push(frame, 0);
  frame.sequence += 3;
  buffer.push(frame, 1'000'000);
  ActuatorFrame out;
  bool concealed = false;
  int played = 0;
  for (std::int64_t t = 0; t < 200'000'000 && played < 100; t += 1'000'000)
    while (buffer.pop(t, out, concealed)) ++played;
  if (buffer.active()) __builtin_trap();  // playout always ends once frames stop
  return 0;
}
