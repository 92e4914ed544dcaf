#pragma once
// Injectable time, so loops, watchdogs and timeouts are tested with a manual clock.
#include <atomic>
#include <cstdint>

namespace vt {

/// Monotonic nanoseconds. Any thread may call now_ns().
class Clock {
 public:
  virtual ~Clock() = default;
  virtual std::int64_t now_ns() const noexcept = 0;
  /// Blocks the calling thread until now_ns() >= deadline_ns (or returns at once when past).
  virtual void sleepUntil(std::int64_t deadline_ns) const noexcept = 0;
  /// Like sleepUntil, but the calling thread keeps its core busy the whole time (never handing
  /// it to the OS), so the wait ends without a wake-up's delay or cold caches. Clocks that only
  /// move when told wait as in sleepUntil.
  virtual void spinUntil(std::int64_t deadline_ns) const noexcept { sleepUntil(deadline_ns); }
};

/// std::chrono::steady_clock; sleepUntil sleeps then spins the last stretch for precision.
class SteadyClock final : public Clock {
 public:
  std::int64_t now_ns() const noexcept override;
  void sleepUntil(std::int64_t deadline_ns) const noexcept override;
  void spinUntil(std::int64_t deadline_ns) const noexcept override;
  /// The process-wide instance.
  static const SteadyClock& instance() noexcept;
};

/// Time that only moves when told; sleepUntil advances it to the deadline.
class ManualClock final : public Clock {
 public:
  explicit ManualClock(std::int64_t start_ns = 0) : m_now_ns(start_ns) {}
  std::int64_t now_ns() const noexcept override { return m_now_ns.load(); }
  void sleepUntil(std::int64_t deadline_ns) const noexcept override;
  void advance(std::int64_t delta_ns) noexcept { m_now_ns.fetch_add(delta_ns); }
  void set(std::int64_t t_ns) noexcept { m_now_ns.store(t_ns); }

 private:
  mutable std::atomic<std::int64_t> m_now_ns;
};

}  // namespace vt
