// The client's whole tactile path on an untrusted datagram: packet decoding, then the frame
// rebuilt through the session codec and format (chosen by the first byte) and the jitter buffer.
#include <cmath>
#include <cstdint>
#include <memory>
#include <span>

#include "vt/net/jitter_buffer.hpp"
#include "vt/net/tactile_stream.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace vt::haptics;
  static const std::unique_ptr<TactileCodec> codecs[] = {
      makeCodec(CodecId::RawFloat32), makeCodec(CodecId::Pcm16), makeCodec(CodecId::Perceptual, 50)};
  if (size < 1) return 0;
  vt::net::StreamContext context;
  context.actuatorCount = 1 + (data[0] >> 2) % 10;
  vt::net::Packet packet;
  if (vt::net::decodeStream(std::span(data + 1, size - 1), context, packet) != vt::net::DecodeStatus::Ok) return 0;
  const auto* tactile = std::get_if<vt::net::Tactile>(&packet.message);
  if (!tactile) return 0;
  const BlockFormat format{context.actuatorCount, kMaxBlockSamples, 8000};
  ActuatorFrame frame;
  bool any = false;
  for (int b = 0; b < tactile->blockCount; ++b) {
    if (!vt::net::unpackFrame(*tactile, b, *codecs[data[0] % 3], format, tactile->frequency_hz, frame)) continue;
    any = true;
    for (const auto& channel : frame.block)
      for (float v : channel)
        if (!std::isfinite(v) || v < -1.0f || v > 1.0f) __builtin_trap();
  }
  if (!any) return 0;
  vt::net::JitterBuffer buffer({4'000'000});
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
