#pragma once
// The offset between a peer's clock and this one (local = peer + offset), estimated NTP-style
// from the timestamps the protocol exchanges: round trips (keep-alive request and reply) give
// offset = ((t1 - t2) + (t4 - t3)) / 2, taken from the exchange with the smallest round trip
// of the recent ones (queueing only ever adds delay); one-way samples (a peer's send time and
// this side's receive time) bound it from above and serve, min-filtered, until the first
// round trip. One thread (the owner's network thread).
#include <array>
#include <cstdint>

namespace vt::net {

/// Min-filtered clock offset estimate; one thread.
class ClockOffset {
 public:
  static constexpr int kWindow = 16;

  /// One round trip this side started: t1 sent here, t2/t3 the peer's receive/send, t4 back here.
  void addRoundTrip(std::int64_t t1, std::int64_t t2, std::int64_t t3, std::int64_t t4) noexcept;
  /// A datagram the peer stamped `peerSent_ns` arrived here at `localReceived_ns`.
  void addOneWay(std::int64_t peerSent_ns, std::int64_t localReceived_ns) noexcept;
  /// True once any sample arrived.
  bool known() const noexcept { return m_roundTrips > 0 || m_oneWays > 0; }
  /// local - peer (ns), 0 before any sample.
  std::int64_t offset_ns() const noexcept;
  /// Round trip of the exchange the offset comes from (0 without one).
  std::int64_t rtt_ns() const noexcept;
  /// `peer_t_ns` on this clock.
  std::int64_t toLocal(std::int64_t peer_t_ns) const noexcept { return peer_t_ns + offset_ns(); }
  void reset() noexcept { *this = ClockOffset{}; }

 private:
  struct RoundTrip {
    std::int64_t rtt_ns = 0;
    std::int64_t offset_ns = 0;
  };
  std::array<RoundTrip, kWindow> m_trips{};
  std::array<std::int64_t, kWindow> m_oneWay{};
  int m_roundTrips = 0, m_oneWays = 0;  // samples so far (the windows hold the last kWindow)
};

}  // namespace vt::net
