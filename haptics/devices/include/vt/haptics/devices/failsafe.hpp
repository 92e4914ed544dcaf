#pragma once
// Decides when actuator output must be forced to zero: shutdown, the process stop request
// (vt/core/stop.hpp: SIGINT/SIGTERM or the program), a stalled
// producer (heartbeat watchdog) or a lost link: the network session's, or the device's own
// (the glove driver reports a failed write or read and a vanished device, and clears it once
// the first report of the new connection, a silent one, is out). The output thread asks every
// tick and sends silent reports while the answer is not None.
#include <atomic>
#include <cstdint>
#include <string>
#include <string_view>

#include "vt/core/clock.hpp"

namespace vt::haptics {

/// Who reports a lost link; each holds output silent until it reports the link back.
enum class Link : std::uint8_t { Network = 1, Device = 2 };

/// Why output is being held silent.
enum class FailsafeReason : std::uint8_t { None = 0, Shutdown, Signal, Stall, LinkLost };
/// Stable lower-case name ("stall", "link-lost", ...).
std::string_view failsafeReasonName(FailsafeReason reason) noexcept;
/// " (silent: REASON)" for a status line, "" when the output is not held silent.
std::string failsafeNote(FailsafeReason reason);

struct FailsafeConfig {
  /// A heartbeat that does not move for this long counts as a stalled producer. With the
  /// writer's 1 ms tick this bounds stall-to-silence at about 21 ms (the budget is 50 ms).
  std::int64_t stallTimeout_ns = 20'000'000;
};

class Failsafe {
 public:
  explicit Failsafe(const Clock& clock, FailsafeConfig config = {}) noexcept : m_clock(clock), m_config(config) {}

  /// Any thread: silence for good (normal exit).
  void requestShutdown() noexcept { m_shutdown.store(true, std::memory_order_release); }
  /// Any thread (the network session, the device driver): silence while `link` is lost, resume
  /// when it returns and no other link is lost.
  void setLinkLost(bool lost, Link link = Link::Network) noexcept {
    const auto bit = std::uint8_t(link);
    if (lost) m_linksLost.fetch_or(bit, std::memory_order_acq_rel);
    else m_linksLost.fetch_and(std::uint8_t(~bit), std::memory_order_acq_rel);
  }
  /// True while any link is lost.
  bool linkLost() const noexcept { return m_linksLost.load(std::memory_order_acquire) != 0; }

  /// Output thread only: `heartbeat` is the producer's current progress counter (it must keep
  /// changing); returns the reason to stay silent now, None when output may be driven.
  FailsafeReason evaluate(std::uint64_t heartbeat) noexcept;
  /// Any thread: the last answer of evaluate().
  FailsafeReason lastReason() const noexcept { return m_lastReason.load(std::memory_order_relaxed); }

 private:
  const Clock& m_clock;
  FailsafeConfig m_config;
  std::atomic<bool> m_shutdown{false};
  std::atomic<std::uint8_t> m_linksLost{0};  // Link bits
  std::atomic<FailsafeReason> m_lastReason{FailsafeReason::None};
  bool m_seenHeartbeat = false;  // output thread only, from here on
  std::uint64_t m_heartbeat = 0;
  std::int64_t m_heartbeatChanged_ns = 0;
};

}  // namespace vt::haptics
