// The authenticated decoders on untrusted datagrams: a keyed server's handshake decoder and a
// keyed session's stream decoder (fixed keys), then the replay window. Forgeries must be
// refused; genuine datagrams built from the input (the first byte's low bit) must open, and
// once opened must be refused as replays.
#include <array>
#include <cstdint>
#include <span>

#include "vt/net/protocol.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace vt::net;
  static const Key key = [] {
    Key k{};
    for (std::size_t i = 0; i < k.size(); ++i) k[i] = std::uint8_t(i * 13 + 1);
    return k;
  }();
  static const SessionKeys keys = deriveSessionKeys(key, 7, {1, 2, 3}, {4, 5, 6});
  if (size < 1) return 0;
  std::span<const std::uint8_t> bytes(data + 1, size - 1);
  StreamContext context;
  context.sessionId = 7;
  context.actuatorCount = 5;
  context.keys = &keys;
  context.receiving = Direction::ClientToServer;
  context.radius_m.fill(0.008f);
  std::array<std::uint8_t, kMaxDatagram> sealed{};
  if (data[0] & 1) {
    // Seal the input as a keep-alive's time and a pose stream's datagram: it must open once.
    KeepAlive keepAlive{false, 0, 0, 0};
    for (std::size_t i = 0; i < std::min<std::size_t>(bytes.size(), 8); ++i) keepAlive.origin_t_ns |= std::int64_t(bytes[i]) << (8 * i);
    const std::uint64_t sequence = 1 + data[0] / 2;
    const std::size_t n = encodeStream(keepAlive, sequence, context, Direction::ClientToServer, sealed);
    if (n == 0) return 0;  // the encoder refuses what the decoder would reject (e.g. out-of-range times)
    bytes = std::span(sealed.data(), n);
  }
  Packet packet;
  RejectCounters counters;
  ReplayWindow window;
  if (looksLikeHandshake(bytes)) {
    const auto status = decodeHandshake(bytes, packet, &key, {}, &counters);
    if (status == DecodeStatus::Ok) __builtin_trap();  // nobody forges the shared key's tag
    return 0;
  }
  const auto status = decodeStream(bytes, context, packet, &counters);
  if ((status == DecodeStatus::Ok) != ((data[0] & 1) != 0)) __builtin_trap();
  if (status != DecodeStatus::Ok) return 0;
  if (!window.fresh(packet.sequence)) __builtin_trap();
  window.accept(packet.sequence);
  if (window.fresh(packet.sequence)) __builtin_trap();  // the same datagram again is a replay
  return 0;
}
