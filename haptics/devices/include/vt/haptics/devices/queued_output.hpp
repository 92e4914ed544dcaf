#pragma once
// What the outputs with a writer thread of their own share (AudioOutput, OscOutput): the queue
// the haptic loop fills, the failsafe their writer obeys, the writer thread and its last error.
// The haptic thread only pushes into the queue; it never waits for the writer.
#include <atomic>
#include <cstddef>
#include <cstdint>
#include <mutex>
#include <string>
#include <string_view>
#include <thread>

#include "vt/core/clock.hpp"
#include "vt/core/spsc_ring.hpp"
#include "vt/haptics/actuator_frame.hpp"
#include "vt/haptics/actuator_sink.hpp"
#include "vt/haptics/devices/failsafe.hpp"

namespace vt::haptics {

class QueuedOutput : public ActuatorSink {
 public:
  /// The writer must have been stopped (each output's destructor calls stop() while what its
  /// writer uses still exists).
  ~QueuedOutput() override;
  QueuedOutput(const QueuedOutput&) = delete;
  QueuedOutput& operator=(const QueuedOutput&) = delete;

  /// The queue the haptic loop writes into (HapticLoop::addOutput; one producer only).
  SpscRing<ActuatorFrame>& queue() noexcept { return m_queue; }
  /// The failsafe the writer obeys (network hook: failsafe().setLinkLost(true)). Any thread.
  Failsafe& failsafe() noexcept { return m_failsafe; }
  /// Asks the writer to put the actuators at rest and end (its last act), and joins it.
  /// Idempotent. Main thread.
  void stop() override;
  /// ActuatorSink: a realtime sink fed through queue().
  SinkThread thread() const override { return SinkThread::Realtime; }
  SinkPort port() override { return m_queue; }

 protected:
  /// `heartbeat`: the haptic loop's tick counter (must outlive the output); nullptr: the
  /// frames the writer popped are the heartbeat.
  QueuedOutput(const Clock& clock, const FailsafeConfig& failsafe, const std::atomic<std::uint64_t>* heartbeat,
               std::size_t queueCapacity);
  /// Starts writerLoop() on a thread of its own at the writers' real-time priority; the last
  /// step of an output's constructor. `threadName` goes into the priority request's log line.
  void startWriter(std::string_view threadName);
  /// The writer: runs until stopping() and leaves the actuators at rest.
  virtual void writerLoop() noexcept = 0;
  /// Writer thread: whether stop() was asked for.
  bool stopping() const noexcept { return m_stopping.load(); }
  /// Writer thread: the producer's progress, given the frames the writer popped so far.
  std::uint64_t heartbeat(std::uint64_t popped) const noexcept {
    return m_heartbeat ? m_heartbeat->load(std::memory_order_relaxed) : popped;
  }
  /// Writer thread: the error the status reports, "what: why" (kept to the counters when memory
  /// runs out: the string is built here, where a failed allocation is caught).
  void setLastError(std::string_view what, std::string_view why) noexcept;
  /// Any non-real-time thread.
  std::string lastError() const;

  const Clock& m_clock;
  Failsafe m_failsafe;
  SpscRing<ActuatorFrame> m_queue;

 private:
  const std::atomic<std::uint64_t>* const m_heartbeat;
  mutable std::mutex m_errorMutex;
  std::string m_lastError;  // guarded by m_errorMutex
  std::atomic<bool> m_stopping{false};
  std::thread m_writer;
};

}  // namespace vt::haptics
