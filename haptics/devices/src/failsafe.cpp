#include "vt/haptics/devices/failsafe.hpp"

#include "vt/core/stop.hpp"

namespace vt::haptics {

std::string failsafeNote(FailsafeReason reason) {
  return reason == FailsafeReason::None ? std::string() : " (silent: " + std::string(failsafeReasonName(reason)) + ")";
}

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
  } else if (stopRequested()) {
    reason = stopSignal() > 0 ? FailsafeReason::Signal : FailsafeReason::Shutdown;
  } else if (linkLost()) {
    reason = FailsafeReason::LinkLost;
  } else if (now - m_heartbeatChanged_ns > m_config.stallTimeout_ns) {
    reason = FailsafeReason::Stall;
  }
  m_lastReason.store(reason, std::memory_order_relaxed);
  return reason;
}

}  // namespace vt::haptics
