// Whole datagrams as the client and server see them from the socket: the handshake decoder,
// and the stream decoder of a plain session (the first byte picks its actuator count and the
// newest sequences the compact fields expand against).
#include <array>
#include <cstdint>
#include <span>

#include "vt/net/protocol.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace vt::net;
  if (size < 1) return 0;
  const std::span<const std::uint8_t> bytes(data + 1, size - 1);
  Packet packet;
  RejectCounters counters;
  std::array<std::uint8_t, kMaxDatagram> out{};
  if (looksLikeHandshake(bytes)) {
    const auto status = decodeHandshake(bytes, packet, nullptr, {}, &counters);
    if ((status == DecodeStatus::Ok) != (counters.total() == 0)) __builtin_trap();
    if (status != DecodeStatus::Ok) return 0;
    // A plain handshake accepted re-encodes to the very same bytes.
    const std::size_t n = encodeHandshake(packet.message, out);
    if (n != bytes.size()) __builtin_trap();
    for (std::size_t i = 0; i < n; ++i)
      if (out[i] != bytes[i]) __builtin_trap();
    return 0;
  }
  StreamContext context;
  context.sessionId = data[0] & 3;
  context.actuatorCount = 1 + (data[0] >> 2) % 10;
  context.newestDatagram = context.newestPose = context.newestFrame = std::uint64_t(data[0]) << 12;
  context.radius_m.fill(0.008f);
  const auto status = decodeStream(bytes, context, packet, &counters);
  if ((status == DecodeStatus::Ok) != (counters.total() == 0)) __builtin_trap();
  if (status != DecodeStatus::Ok) return 0;
  // Anything accepted re-encodes (quantised poses may pick another equivalent form), and that
  // decodes again.
  const std::size_t n = encodeStream(packet.message, packet.sequence, context, Direction::ServerToClient, out);
  if (n == 0) __builtin_trap();
  Packet again;
  if (decodeStream(std::span(out.data(), n), context, again) != DecodeStatus::Ok) __builtin_trap();
  return 0;
}
