#pragma once
// A clock the test moves by hand while other threads sleep on it, so a thread's ticks are
// counted in simulated time, exactly, whatever the machine's load (vt::ManualClock instead lets
// each sleeper jump time forward itself, which suits one thread only).
#include <algorithm>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <limits>
#include <mutex>
#include <vector>

#include "vt/core/clock.hpp"

namespace vt::test {

class SteppedClock final : public Clock {
 public:
  explicit SteppedClock(std::int64_t start_ns = 0) : m_now_ns(start_ns) {}

  std::int64_t now_ns() const noexcept override {
    const std::lock_guard lock(m_mutex);
    return m_now_ns;
  }

  /// Blocks until the test has moved time to `deadline_ns` (at once after runFree()).
  void sleepUntil(std::int64_t deadline_ns) const noexcept override {
    std::unique_lock lock(m_mutex);
    if (m_free) {
      m_now_ns = std::max(m_now_ns, deadline_ns);
      return;
    }
    ++m_sleeps;
    m_deadlines.push_back(deadline_ns);
    m_changed.notify_all();
    m_changed.wait(lock, [&] { return m_free || m_now_ns >= deadline_ns; });
    m_deadlines.erase(std::find(m_deadlines.begin(), m_deadlines.end(), deadline_ns));
    m_now_ns = std::max(m_now_ns, deadline_ns);
  }

  /// Calls of sleepUntil so far (a sleeping thread that was woken has returned to it when this grows).
  std::uint64_t sleeps() const {
    const std::lock_guard lock(m_mutex);
    return m_sleeps;
  }
  /// Threads asleep now.
  std::size_t sleepers() const {
    const std::lock_guard lock(m_mutex);
    return m_deadlines.size();
  }
  /// The earliest deadline a thread sleeps to (int64 max when none sleeps).
  std::int64_t nextDeadline() const {
    const std::lock_guard lock(m_mutex);
    std::int64_t next = std::numeric_limits<std::int64_t>::max();
    for (std::int64_t d : m_deadlines) next = std::min(next, d);
    return next;
  }
  /// Waits (real time, up to `limit_ms`) until sleeps() exceeds `count`; false on time-out.
  bool waitForSleepsAbove(std::uint64_t count, int limit_ms = 5000) const {
    std::unique_lock lock(m_mutex);
    return m_changed.wait_for(lock, std::chrono::milliseconds(limit_ms), [&] { return m_sleeps > count; });
  }
  /// Moves time forward to `t_ns` and wakes the threads whose deadline it reached.
  void advanceTo(std::int64_t t_ns) {
    const std::lock_guard lock(m_mutex);
    m_now_ns = std::max(m_now_ns, t_ns);
    m_changed.notify_all();
  }
  /// From now on sleepUntil returns at once (time jumps to the deadline): lets threads finish.
  void runFree() {
    const std::lock_guard lock(m_mutex);
    m_free = true;
    m_changed.notify_all();
  }

 private:
  mutable std::mutex m_mutex;
  mutable std::condition_variable m_changed;
  mutable std::int64_t m_now_ns;
  mutable std::uint64_t m_sleeps = 0;
  mutable std::vector<std::int64_t> m_deadlines;
  bool m_free = false;
};

}  // namespace vt::test
