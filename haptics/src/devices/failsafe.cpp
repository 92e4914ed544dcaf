#include "vt/haptics/devices/failsafe.hpp"

#include <unistd.h>

#include <csignal>

#include "vt/core/error.hpp"

namespace vt::haptics {
namespace {

// Lock-free atomics are async-signal-safe; the handler does nothing else but count and store.
std::atomic<int> g_signal{0};
static_assert(std::atomic<int>::is_always_lock_free);

extern "C" void onTerminationSignal(int signal) {
  if (g_signal.exchange(signal) != 0) _exit(128 + signal);  // second signal: the user insists
}

}  // namespace

std::string_view failsafeReasonName(FailsafeReason reason) noexcept {
  switch (reason) {
    case FailsafeReason::None: return "none";
    case FailsafeReason::Shutdown: return "shutdown";
    case FailsafeReason::Signal: return "signal";
    case FailsafeReason::Stall: return "stall";
    case FailsafeReason::LinkLost: return "link-lost";
  }
  return "unknown";
}

FailsafeReason Failsafe::evaluate(std::uint64_t heartbeat) noexcept {
  const std::int64_t now = m_clock.now_ns();
  if (!m_seenHeartbeat || heartbeat != m_heartbeat) {
    m_seenHeartbeat = true;
    m_heartbeat = heartbeat;
    m_heartbeatChanged_ns = now;
  }
  FailsafeReason reason = FailsafeReason::None;
  if (m_shutdown.load(std::memory_order_acquire)) {
    reason = FailsafeReason::Shutdown;
  } else if (receivedSignal() != 0) {
    reason = FailsafeReason::Signal;
  } else if (m_linkLost.load(std::memory_order_acquire)) {
    reason = FailsafeReason::LinkLost;
  } else if (now - m_heartbeatChanged_ns > m_config.stallTimeout_ns) {
    reason = FailsafeReason::Stall;
  }
  m_lastReason.store(reason, std::memory_order_relaxed);
  return reason;
}

void installSignalFailsafe() {
  struct sigaction action {};
  action.sa_handler = onTerminationSignal;
  sigemptyset(&action.sa_mask);
  for (int signal : {SIGINT, SIGTERM}) {
    if (sigaction(signal, &action, nullptr) != 0) fail("failsafe: sigaction(", signal, ") failed");
  }
}

int receivedSignal() noexcept { return g_signal.load(); }

void clearReceivedSignal() noexcept { g_signal.store(0); }

}  // namespace vt::haptics
