// Whole-datagram decoding as the client and server see it from the socket.
#include <array>
#include <cstdint>
#include <span>

#include "vt/net/protocol.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  vt::net::Packet packet;
  vt::net::RejectCounters counters;
  const auto status = vt::net::decodePacket(std::span(data, size), packet, &counters);
  if ((status == vt::net::DecodeStatus::Ok) != (counters.total() == 0)) __builtin_trap();
  if (status == vt::net::DecodeStatus::Ok) {
    // Anything accepted re-encodes to the very same bytes (modulo nothing).
    std::array<std::uint8_t, vt::net::kMaxDatagram> out{};
    const std::size_t n = vt::net::encodePacket(packet, out);
    if (n != size) __builtin_trap();
    for (std::size_t i = 0; i < n; ++i)
      if (out[i] != data[i]) __builtin_trap();
  }
  return 0;
}
