#pragma once
// UDP over POSIX sockets (IPv4 and IPv6), with an optional receive-side impairment layer for
// tests and benchmarks: seeded loss, delay, jitter and reordering, applied before a datagram is
// handed to the caller. One thread receives; any thread may send.
#include <array>
#include <atomic>
#include <cstdint>
#include <random>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "vt/net/protocol.hpp"

namespace vt::net {

/// An IPv4 or IPv6 address and port. IPv4 addresses are held IPv4-mapped (::ffff:A.B.C.D, RFC
/// 4291 2.5.5.2), as a dual-stack socket reports them, so one value compares and prints both.
struct Endpoint {
  std::array<std::uint8_t, 16> address{0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0xFF, 0xFF, 127, 0, 0, 1};  // 127.0.0.1
  std::uint16_t port = 0;
  bool operator==(const Endpoint&) const = default;

  /// An IPv4 endpoint from the address in host byte order.
  static constexpr Endpoint ipv4(std::uint32_t address, std::uint16_t port) noexcept {
    Endpoint e;
    for (int i = 0; i < 4; ++i) e.address[std::size_t(12 + i)] = std::uint8_t(address >> (24 - 8 * i));
    e.port = port;
    return e;
  }
  /// Whether the address is IPv4 (IPv4-mapped).
  bool isIpv4() const noexcept;
  /// 127.0.0.0/8, ::1 (and 127/8 mapped): the datagrams never leave this machine.
  bool isLoopback() const noexcept;
};

/// Parses "HOST:PORT" (port 0..65535): HOST an IPv4 address, a bracketed IPv6 address
/// ("[::1]:47800") or a host name, resolved with getaddrinfo (its IPv4 address when it has both,
/// as the server binds IPv4 loopback by default). Setup only: resolving may block. Throws
/// vt::Error naming `what`, the text and why.
Endpoint parseEndpoint(std::string_view text, std::string_view what = "address");
/// "A.B.C.D:PORT" or "[IPV6]:PORT".
std::string toString(const Endpoint& endpoint);
/// The address a client binds to reach `server`: loopback of the server's family for a server on
/// this machine, else any address of that family (port 0: the kernel chooses).
Endpoint localEndpointFor(const Endpoint& server) noexcept;

/// Network faults injected on receive (all off by default). Deterministic for a given seed.
struct Impairment {
  double loss = 0.0;                 // probability a datagram is dropped
  std::int64_t delay_ns = 0;         // constant extra one-way delay
  std::int64_t jitter_ns = 0;        // + uniform 0..jitter_ns
  double reorder = 0.0;              // probability a datagram is held back an extra reorderDelay_ns
  std::int64_t reorderDelay_ns = 2'000'000;
  std::uint64_t seed = 1;
  bool active() const noexcept { return loss > 0 || delay_ns > 0 || jitter_ns > 0 || reorder > 0; }
};

/// Counters of one transport; any thread may read.
struct TransportStats {
  std::uint64_t sent = 0;
  std::uint64_t sendFailures = 0;
  std::uint64_t received = 0;
  std::uint64_t impairedDrops = 0;  // dropped by the impairment layer (loss or queue full)
  std::uint64_t impairedDelayed = 0;
};

/// One bound UDP socket plus the impairment layer: receive on one thread, send from any.
class Transport {
 public:
  /// Binds `local` (port 0 = any free port) on a socket of its family (an IPv6 socket also takes
  /// IPv4 peers, mapped). Throws vt::Error naming the address and errno text.
  explicit Transport(const Endpoint& local, const Impairment& impairment = {});
  ~Transport();
  Transport(const Transport&) = delete;
  Transport& operator=(const Transport&) = delete;

  /// The bound address (with the port the kernel chose).
  Endpoint localEndpoint() const noexcept { return m_local; }
  /// Any thread. False (and counted) when the kernel refuses the datagram.
  bool send(std::span<const std::uint8_t> datagram, const Endpoint& to) noexcept;
  /// Receiving thread only. Waits until a datagram is available or SteadyClock reaches
  /// deadline_ns; returns its real size (which may exceed buffer.size(): then only the buffer
  /// was filled and the caller rejects it as oversized) or 0 at the deadline.
  std::size_t receive(std::span<std::uint8_t> buffer, Endpoint& from, std::int64_t deadline_ns) noexcept;
  TransportStats stats() const noexcept;

 private:
  struct Held {
    std::int64_t due_ns = 0;
    Endpoint from;
    std::size_t size = 0;
    std::array<std::uint8_t, kMaxDatagram + 1> bytes{};
  };
  std::size_t receiveRaw(std::span<std::uint8_t> buffer, Endpoint& from, std::int64_t deadline_ns) noexcept;
  std::size_t releaseHeld(std::span<std::uint8_t> buffer, Endpoint& from, std::int64_t now_ns) noexcept;

  int m_fd = -1;
  bool m_ipv6 = false;  // the socket is AF_INET6 (else AF_INET: IPv4 peers only)
  Endpoint m_local;
  Impairment m_impairment;
  std::mt19937_64 m_rng;
  std::vector<Held> m_held;  // capacity fixed at construction
  std::size_t m_heldCount = 0;
  std::atomic<std::uint64_t> m_sent{0}, m_sendFailures{0}, m_received{0}, m_drops{0}, m_delayed{0};
};

}  // namespace vt::net
