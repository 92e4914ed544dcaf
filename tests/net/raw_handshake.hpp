#pragma once
// The client's side of the handshake done by hand, for tests that speak the protocol directly:
// hello, the server's challenge, the hello again with its cookie.
#include <array>
#include <cstdint>
#include <vector>

#include "vt/core/clock.hpp"
#include "vt/net/protocol.hpp"
#include "vt/net/transport.hpp"

namespace vt::net::test {

/// One hello datagram as sent (kept to replay it) and its nonce (keyed).
struct SentHello {
  std::vector<std::uint8_t> bytes;
  std::array<std::uint8_t, kNonceSize> nonce{};
};

/// The next answer to `hello` (decoded into `packet`, opened with `key`); false after 2 s of silence.
inline bool receiveAnswer(Transport& raw, const SentHello& hello, Packet& packet, const Key* key = nullptr,
                          std::int64_t wait_ns = 2'000'000'000) {
  std::array<std::uint8_t, kMaxDatagram + 1> bytes{};
  Endpoint from;
  const std::size_t size = raw.receive(bytes, from, SteadyClock::instance().now_ns() + wait_ns);
  if (size == 0) return false;
  return decodeHandshake(std::span(bytes.data(), size), packet, key, std::span(&hello.nonce, 1)) == DecodeStatus::Ok;
}

/// Sends `hello` (sealed with `key` when given) and returns what was sent.
inline SentHello sendHello(Transport& raw, const Endpoint& server, const Hello& hello, const Key* key = nullptr) {
  SentHello sent;
  sent.bytes.resize(kMaxDatagram);
  sent.bytes.resize(encodeHandshake(hello, sent.bytes, key, &sent.nonce));
  raw.send(sent.bytes, server);
  return sent;
}

/// The whole handshake: true with the server's final answer (accept or refuse) in `packet`;
/// `sent` (optional) receives both hellos as sent.
inline bool rawHandshake(Transport& raw, const Endpoint& server, Hello hello, Packet& packet, const Key* key = nullptr,
                         std::vector<SentHello>* sent = nullptr) {
  SentHello first = sendHello(raw, server, hello, key);
  if (!receiveAnswer(raw, first, packet, key)) return false;
  if (sent) sent->push_back(first);
  const auto* challenge = std::get_if<Challenge>(&packet.message);
  if (!challenge) return true;
  hello.cookie = challenge->cookie;
  SentHello second = sendHello(raw, server, hello, key);
  if (sent) sent->push_back(second);
  return receiveAnswer(raw, second, packet, key);
}

}  // namespace vt::net::test
