#include "vt/net/transport.hpp"

#include <arpa/inet.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <cstring>
#include <limits>

#include "vt/core/clock.hpp"
#include "vt/core/error.hpp"

namespace vt::net {

namespace {

constexpr std::size_t kHeldCapacity = 256;

sockaddr_in toSockaddr(const Endpoint& e) noexcept {
  sockaddr_in addr{};
  addr.sin_family = AF_INET;
  addr.sin_port = htons(e.port);
  addr.sin_addr.s_addr = htonl(e.address);
  return addr;
}

}  // namespace

Endpoint parseEndpoint(std::string_view text, std::string_view what) {
  const auto colon = text.rfind(':');
  if (colon == std::string_view::npos) fail(what, " '", text, "': expected ADDR:PORT (e.g. 127.0.0.1:47800)");
  const std::string host(text.substr(0, colon));
  const std::string_view portText = text.substr(colon + 1);
  unsigned port = 0;
  const auto [end, ec] = std::from_chars(portText.data(), portText.data() + portText.size(), port);
  if (ec != std::errc() || end != portText.data() + portText.size() || port > 65535 || portText.empty())
    fail(what, " '", text, "': port must be a number 0..65535");
  in_addr addr{};
  if (inet_pton(AF_INET, host.c_str(), &addr) != 1) fail(what, " '", text, "': '", host, "' is not an IPv4 address");
  return {ntohl(addr.s_addr), std::uint16_t(port)};
}

std::string toString(const Endpoint& e) {
  return str((e.address >> 24) & 255, '.', (e.address >> 16) & 255, '.', (e.address >> 8) & 255, '.', e.address & 255,
             ':', e.port);
}

Transport::Transport(const Endpoint& local, const Impairment& impairment)
    : m_impairment(impairment), m_rng(impairment.seed), m_held(kHeldCapacity) {
  m_fd = ::socket(AF_INET, SOCK_DGRAM | SOCK_CLOEXEC, 0);
  if (m_fd < 0) fail("udp socket for ", toString(local), ": ", std::strerror(errno));
  // A larger receive buffer rides out bursts (the kernel caps it at net.core.rmem_max).
  const int bufferBytes = 1 << 20;
  ::setsockopt(m_fd, SOL_SOCKET, SO_RCVBUF, &bufferBytes, sizeof bufferBytes);
  const sockaddr_in addr = toSockaddr(local);
  if (::bind(m_fd, reinterpret_cast<const sockaddr*>(&addr), sizeof addr) != 0) {
    const int err = errno;
    ::close(m_fd);
    fail("cannot bind udp ", toString(local), ": ", std::strerror(err));
  }
  sockaddr_in bound{};
  socklen_t length = sizeof bound;
  ::getsockname(m_fd, reinterpret_cast<sockaddr*>(&bound), &length);
  m_local = {ntohl(bound.sin_addr.s_addr), ntohs(bound.sin_port)};
}

Transport::~Transport() {
  if (m_fd >= 0) ::close(m_fd);
}

bool Transport::send(std::span<const std::uint8_t> datagram, const Endpoint& to) noexcept {
  const sockaddr_in addr = toSockaddr(to);
  const ssize_t n = ::sendto(m_fd, datagram.data(), datagram.size(), MSG_NOSIGNAL,
                             reinterpret_cast<const sockaddr*>(&addr), sizeof addr);
  if (n != ssize_t(datagram.size())) {
    m_sendFailures.fetch_add(1, std::memory_order_relaxed);
    return false;
  }
  m_sent.fetch_add(1, std::memory_order_relaxed);
  return true;
}

std::size_t Transport::receiveRaw(std::span<std::uint8_t> buffer, Endpoint& from, std::int64_t deadline_ns) noexcept {
  for (;;) {
    const std::int64_t wait_ns = deadline_ns - SteadyClock::instance().now_ns();
    pollfd pfd{m_fd, POLLIN, 0};
    const timespec timeout{std::max<std::int64_t>(wait_ns, 0) / 1'000'000'000, std::max<std::int64_t>(wait_ns, 0) % 1'000'000'000};
    const int ready = ::ppoll(&pfd, 1, &timeout, nullptr);
    if (ready < 0 && errno == EINTR) continue;
    if (ready <= 0) return 0;
    sockaddr_in addr{};
    socklen_t length = sizeof addr;
    // MSG_TRUNC: the real size comes back even when it exceeds the buffer (-> "oversized").
    const ssize_t n = ::recvfrom(m_fd, buffer.data(), buffer.size(), MSG_TRUNC, reinterpret_cast<sockaddr*>(&addr), &length);
    if (n <= 0) {
      if (n < 0 && (errno == EINTR || errno == EAGAIN)) continue;
      if (n == 0) continue;  // empty datagram: nothing to deliver
      return 0;
    }
    from = {ntohl(addr.sin_addr.s_addr), ntohs(addr.sin_port)};
    m_received.fetch_add(1, std::memory_order_relaxed);
    return std::size_t(n);
  }
}

std::size_t Transport::releaseHeld(std::span<std::uint8_t> buffer, Endpoint& from, std::int64_t now_ns) noexcept {
  std::size_t best = m_heldCount;
  for (std::size_t i = 0; i < m_heldCount; ++i)
    if (m_held[i].due_ns <= now_ns && (best == m_heldCount || m_held[i].due_ns < m_held[best].due_ns)) best = i;
  if (best == m_heldCount) return 0;
  Held& held = m_held[best];
  from = held.from;
  const std::size_t size = held.size;
  std::memcpy(buffer.data(), held.bytes.data(), std::min(size, std::min(buffer.size(), held.bytes.size())));
  std::swap(m_held[best], m_held[--m_heldCount]);
  return size;
}

std::size_t Transport::receive(std::span<std::uint8_t> buffer, Endpoint& from, std::int64_t deadline_ns) noexcept {
  if (!m_impairment.active()) return receiveRaw(buffer, from, deadline_ns);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (;;) {
    const std::int64_t now = SteadyClock::instance().now_ns();
    if (const std::size_t n = releaseHeld(buffer, from, now)) return n;
    std::int64_t wake = deadline_ns;
    for (std::size_t i = 0; i < m_heldCount; ++i) wake = std::min(wake, m_held[i].due_ns);
    if (now >= deadline_ns && wake >= deadline_ns) return 0;
    Held incoming;
    const std::size_t n = receiveRaw(std::span(incoming.bytes), incoming.from, wake);
    if (n == 0) {
      if (SteadyClock::instance().now_ns() >= deadline_ns && m_heldCount == 0) return 0;
      continue;
    }
    if (unit(m_rng) < m_impairment.loss) {
      m_drops.fetch_add(1, std::memory_order_relaxed);
      continue;
    }
    std::int64_t delay = m_impairment.delay_ns;
    if (m_impairment.jitter_ns > 0) delay += std::int64_t(unit(m_rng) * double(m_impairment.jitter_ns));
    if (unit(m_rng) < m_impairment.reorder) delay += m_impairment.reorderDelay_ns;
    if (delay <= 0) {
      from = incoming.from;
      std::memcpy(buffer.data(), incoming.bytes.data(), std::min(n, std::min(buffer.size(), incoming.bytes.size())));
      return n;
    }
    if (m_heldCount == m_held.size()) {
      m_drops.fetch_add(1, std::memory_order_relaxed);
      continue;
    }
    incoming.due_ns = SteadyClock::instance().now_ns() + delay;
    incoming.size = n;
    m_held[m_heldCount++] = incoming;
    m_delayed.fetch_add(1, std::memory_order_relaxed);
  }
}

TransportStats Transport::stats() const noexcept {
  return {m_sent.load(), m_sendFailures.load(), m_received.load(), m_drops.load(), m_delayed.load()};
}

}  // namespace vt::net
