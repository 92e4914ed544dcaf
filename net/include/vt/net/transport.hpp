#pragma once
// UDP over POSIX sockets (IPv4), with an optional receive-side impairment layer for tests and
// benchmarks: seeded loss, delay, jitter and reordering, applied before a datagram is handed
// to the caller. One thread receives; any thread may send.
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

/// An IPv4 address and port (host byte order).
struct Endpoint {
  std::uint32_t address = 0x7F000001;  // 127.0.0.1
  std::uint16_t port = 0;
  bool operator==(const Endpoint&) const = default;
};

/// Parses "A.B.C.D:PORT" (port 0..65535). Throws vt::Error naming `what` and the text.
Endpoint parseEndpoint(std::string_view text, std::string_view what = "address");
/// "A.B.C.D:PORT".
std::string toString(const Endpoint& endpoint);

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
  /// Binds `local` (port 0 = any free port). Throws vt::Error naming the address and errno text.
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
  Endpoint m_local;
  Impairment m_impairment;
  std::mt19937_64 m_rng;
  std::vector<Held> m_held;  // capacity fixed at construction
  std::size_t m_heldCount = 0;
  std::atomic<std::uint64_t> m_sent{0}, m_sendFailures{0}, m_received{0}, m_drops{0}, m_delayed{0};
};

}  // namespace vt::net
