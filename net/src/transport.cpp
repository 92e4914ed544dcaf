#include "vt/net/transport.hpp"

#include <arpa/inet.h>
#include <netdb.h>
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
constexpr std::array<std::uint8_t, 12> kMappedPrefix{0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0xFF, 0xFF};

// The socket address for `e` on a socket of the given family; false when an IPv4 socket is asked
// for an IPv6 address.
bool toSockaddr(const Endpoint& e, bool ipv6, sockaddr_storage& out, socklen_t& length) noexcept {
  out = {};
  if (ipv6) {
    auto& a = reinterpret_cast<sockaddr_in6&>(out);
    a.sin6_family = AF_INET6;
    a.sin6_port = htons(e.port);
    std::memcpy(a.sin6_addr.s6_addr, e.address.data(), 16);
    length = sizeof a;
    return true;
  }
  if (!e.isIpv4()) return false;
  auto& a = reinterpret_cast<sockaddr_in&>(out);
  a.sin_family = AF_INET;
  a.sin_port = htons(e.port);
  std::memcpy(&a.sin_addr.s_addr, e.address.data() + 12, 4);
  length = sizeof a;
  return true;
}

Endpoint fromSockaddr(const sockaddr_storage& in) noexcept {
  Endpoint e;
  if (in.ss_family == AF_INET6) {
    const auto& a = reinterpret_cast<const sockaddr_in6&>(in);
    std::memcpy(e.address.data(), a.sin6_addr.s6_addr, 16);
    e.port = ntohs(a.sin6_port);
  } else {
    const auto& a = reinterpret_cast<const sockaddr_in&>(in);
    std::memcpy(e.address.data(), kMappedPrefix.data(), 12);
    std::memcpy(e.address.data() + 12, &a.sin_addr.s_addr, 4);
    e.port = ntohs(a.sin_port);
  }
  return e;
}

// HOST's addresses from getaddrinfo: the first IPv4 one, else the first IPv6 one; `numeric`: an
// IPv6 address only (it was in brackets).
Endpoint resolve(const std::string& host, bool numeric, std::uint16_t port, std::string_view what, std::string_view text) {
  addrinfo hints{};
  hints.ai_family = numeric ? AF_INET6 : AF_UNSPEC;  // brackets hold an IPv6 address
  hints.ai_socktype = SOCK_DGRAM;
  hints.ai_flags = numeric ? AI_NUMERICHOST : 0;
  addrinfo* found = nullptr;
  if (const int e = ::getaddrinfo(host.c_str(), nullptr, &hints, &found); e != 0) {
    if (numeric) fail(what, " '", text, "': '", host, "' is not an IPv6 address");
    fail(what, " '", text, "': cannot resolve '", host, "': ", ::gai_strerror(e));
  }
  const addrinfo* chosen = nullptr;
  for (const addrinfo* a = found; a; a = a->ai_next) {
    if (a->ai_family == AF_INET) {
      chosen = a;
      break;
    }
    if (a->ai_family == AF_INET6 && !chosen) chosen = a;
  }
  Endpoint out;
  const bool usable = chosen != nullptr;
  if (usable) {
    sockaddr_storage address{};
    std::memcpy(&address, chosen->ai_addr, std::min<std::size_t>(chosen->ai_addrlen, sizeof address));
    out = fromSockaddr(address);
  }
  ::freeaddrinfo(found);
  if (!usable) fail(what, " '", text, "': '", host, "' has no IPv4 or IPv6 address");
  out.port = port;
  return out;
}

}  // namespace

bool Endpoint::isIpv4() const noexcept { return std::equal(kMappedPrefix.begin(), kMappedPrefix.end(), address.begin()); }

bool Endpoint::isLoopback() const noexcept {
  if (isIpv4()) return address[12] == 127;
  constexpr std::array<std::uint8_t, 16> kLoopback6{0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 1};
  return address == kLoopback6;
}

Endpoint parseEndpoint(std::string_view text, std::string_view what) {
  const auto colon = text.rfind(':');
  if (colon == std::string_view::npos)
    fail(what, " '", text, "': expected HOST:PORT (e.g. 127.0.0.1:47800, localhost:47800 or [::1]:47800)");
  std::string_view host = text.substr(0, colon);
  const std::string_view portText = text.substr(colon + 1);
  unsigned port = 0;
  const auto [end, ec] = std::from_chars(portText.data(), portText.data() + portText.size(), port);
  if (ec != std::errc() || end != portText.data() + portText.size() || port > 65535 || portText.empty())
    fail(what, " '", text, "': port must be a number 0..65535");
  const bool bracketed = host.size() >= 2 && host.front() == '[' && host.back() == ']';
  if (bracketed) host = host.substr(1, host.size() - 2);
  else if (host.find(':') != std::string_view::npos)
    fail(what, " '", text, "': an IPv6 address goes in brackets ([", host, "]:", portText, ")");
  if (host.empty()) fail(what, " '", text, "': no host before the port");
  return resolve(std::string(host), bracketed, std::uint16_t(port), what, text);
}

std::string toString(const Endpoint& e) {
  if (e.isIpv4()) return str(int(e.address[12]), '.', int(e.address[13]), '.', int(e.address[14]), '.', int(e.address[15]), ':', e.port);
  char text[INET6_ADDRSTRLEN] = "?";
  in6_addr address{};
  std::memcpy(address.s6_addr, e.address.data(), 16);
  ::inet_ntop(AF_INET6, &address, text, sizeof text);
  return str('[', text, "]:", e.port);
}

Endpoint localEndpointFor(const Endpoint& server) noexcept {
  Endpoint local;  // IPv4 loopback
  if (!server.isIpv4()) {
    local.address = {};  // :: (any), or ::1 for a server on this machine
    local.address[15] = server.isLoopback() ? 1 : 0;
  }
  else if (!server.isLoopback()) local = Endpoint::ipv4(0, 0);
  local.port = 0;
  return local;
}

Transport::Transport(const Endpoint& local, const Impairment& impairment)
    : m_ipv6(!local.isIpv4()), m_impairment(impairment), m_rng(impairment.seed), m_held(kHeldCapacity) {
  m_fd = ::socket(m_ipv6 ? AF_INET6 : AF_INET, SOCK_DGRAM | SOCK_CLOEXEC, 0);
  if (m_fd < 0) fail("udp socket for ", toString(local), ": ", std::strerror(errno));
  if (m_ipv6) {
    // Dual stack whatever the system default: "[::]:PORT" also serves IPv4 clients.
    const int off = 0;
    ::setsockopt(m_fd, IPPROTO_IPV6, IPV6_V6ONLY, &off, sizeof off);
  }
  // A larger receive buffer rides out bursts (the kernel caps it at net.core.rmem_max).
  const int bufferBytes = 1 << 20;
  ::setsockopt(m_fd, SOL_SOCKET, SO_RCVBUF, &bufferBytes, sizeof bufferBytes);
  sockaddr_storage addr{};
  socklen_t length = 0;
  toSockaddr(local, m_ipv6, addr, length);
  if (::bind(m_fd, reinterpret_cast<const sockaddr*>(&addr), length) != 0) {
    const int err = errno;
    ::close(m_fd);
    fail("cannot bind udp ", toString(local), ": ", std::strerror(err));
  }
  sockaddr_storage bound{};
  socklen_t boundLength = sizeof bound;
  ::getsockname(m_fd, reinterpret_cast<sockaddr*>(&bound), &boundLength);
  m_local = fromSockaddr(bound);
}

Transport::~Transport() {
  if (m_fd >= 0) ::close(m_fd);
}

bool Transport::send(std::span<const std::uint8_t> datagram, const Endpoint& to) noexcept {
  sockaddr_storage addr{};
  socklen_t length = 0;
  const bool reachable = toSockaddr(to, m_ipv6, addr, length);  // an IPv4 socket cannot reach IPv6
  const ssize_t n = reachable ? ::sendto(m_fd, datagram.data(), datagram.size(), MSG_NOSIGNAL,
                                         reinterpret_cast<const sockaddr*>(&addr), length)
                              : -1;
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
    sockaddr_storage addr{};
    socklen_t length = sizeof addr;
    // MSG_TRUNC: the real size comes back even when it exceeds the buffer (-> "oversized").
    const ssize_t n = ::recvfrom(m_fd, buffer.data(), buffer.size(), MSG_TRUNC, reinterpret_cast<sockaddr*>(&addr), &length);
    if (n <= 0) {
      if (n < 0 && (errno == EINTR || errno == EAGAIN)) continue;
      if (n == 0) continue;  // empty datagram: nothing to deliver
      return 0;
    }
    from = fromSockaddr(addr);
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
