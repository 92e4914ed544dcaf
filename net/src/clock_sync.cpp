#include "vt/net/clock_sync.hpp"

#include <algorithm>

namespace vt::net {

void ClockOffset::addRoundTrip(std::int64_t t1, std::int64_t t2, std::int64_t t3, std::int64_t t4) noexcept {
  const std::int64_t rtt = (t4 - t1) - (t3 - t2);
  if (rtt < 0 || t3 < t2) return;  // inconsistent stamps (a clock stepped): not a sample
  m_trips[std::size_t(m_roundTrips % kWindow)] = {rtt, ((t1 - t2) + (t4 - t3)) / 2};
  ++m_roundTrips;
}

void ClockOffset::addOneWay(std::int64_t peerSent_ns, std::int64_t localReceived_ns) noexcept {
  m_oneWay[std::size_t(m_oneWays % kWindow)] = localReceived_ns - peerSent_ns;
  ++m_oneWays;
}

std::int64_t ClockOffset::offset_ns() const noexcept {
  if (m_roundTrips > 0) {
    const int n = std::min(m_roundTrips, kWindow);
    const auto best = std::min_element(m_trips.begin(), m_trips.begin() + n,
                                       [](const RoundTrip& a, const RoundTrip& b) { return a.rtt_ns < b.rtt_ns; });
    return best->offset_ns;
  }
  if (m_oneWays > 0) return *std::min_element(m_oneWay.begin(), m_oneWay.begin() + std::min(m_oneWays, kWindow));
  return 0;
}

std::int64_t ClockOffset::rtt_ns() const noexcept {
  if (m_roundTrips == 0) return 0;
  const int n = std::min(m_roundTrips, kWindow);
  return std::min_element(m_trips.begin(), m_trips.begin() + n,
                          [](const RoundTrip& a, const RoundTrip& b) { return a.rtt_ns < b.rtt_ns; })
      ->rtt_ns;
}

}  // namespace vt::net
