#include "vt/haptics/devices/queued_output.hpp"

#include <cassert>

#include "vt/core/realtime.hpp"

namespace vt::haptics {
namespace {

// The writers' priority: real time (a late write is a gap in the signal, and a lab device
// listening at 1 kHz sees the loop's timing), but below the haptic loop (20): the producer must
// never wait for one of its sinks.
constexpr int kOutputWriterPriority = 15;

}  // namespace

QueuedOutput::QueuedOutput(const Clock& clock, const FailsafeConfig& failsafe,
                           const std::atomic<std::uint64_t>* heartbeat, std::size_t queueCapacity)
    : m_clock(clock), m_failsafe(clock, failsafe), m_queue(queueCapacity), m_heartbeat(heartbeat) {}

QueuedOutput::~QueuedOutput() { assert(!m_writer.joinable() && "an output's destructor must call stop()"); }

void QueuedOutput::startWriter(std::string_view threadName) {
  m_writer = std::thread([this, name = std::string(threadName)] {
    requestRealtime(name, kOutputWriterPriority);
    writerLoop();
  });
}

void QueuedOutput::stop() {
  m_failsafe.requestShutdown();
  m_stopping.store(true);
  if (m_writer.joinable()) m_writer.join();
}

void QueuedOutput::setLastError(std::string_view what, std::string_view why) noexcept {
  try {
    const std::lock_guard lock(m_errorMutex);
    m_lastError.assign(what).append(": ").append(why);
  } catch (...) {  // allocation only; the output's counters still say it
  }
}

std::string QueuedOutput::lastError() const {
  const std::lock_guard lock(m_errorMutex);
  return m_lastError;
}

}  // namespace vt::haptics
