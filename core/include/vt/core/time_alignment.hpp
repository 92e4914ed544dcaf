#pragma once
// The one rule that places actuator output in time (docs/ARCHITECTURE.md, "Time"): a frame made
// at time t is felt at t + the felt outputs' latency, and the display shows the hand as it was
// a display lag earlier, so the frame must render the hand at
//     hand time = t + lead,   lead = felt latency - display lag.
// The haptic loop applies it to every tick, a network client to every pose it sends (its lead
// also covers the stream's round trip). A lead that changes is slewed in: the hand's time then
// runs at (1 +- kSlew) x real time, never standing still (a frozen contact) or jumping.
#include <atomic>
#include <cstdint>

namespace vt {

class LeadSlew {
 public:
  /// Largest change of the hand's time per unit of real time while a new lead is slewed in.
  static constexpr double kSlew = 0.1;

  /// The lead to use at t_ns, moved towards `target_ns`; taken at once on the first call and
  /// when `felt` is false (nothing touches, so a jump of the hand's time cannot be felt).
  /// Allocation-free and lock-free (the haptic thread calls it every tick); one caller thread.
  std::int64_t advance(std::int64_t t_ns, std::int64_t target_ns, bool felt = true) noexcept;
  /// Takes `lead_ns` as is from t_ns on (a replayed tick reproduces its recorded hand time).
  void set(std::int64_t t_ns, std::int64_t lead_ns) noexcept {
    m_lead_ns.store(lead_ns, std::memory_order_relaxed);
    m_last_ns = t_ns;
    m_started = true;
  }
  /// The lead in use. Any thread: the display paces its frames to it (app/modes/present_pacer.hpp).
  std::int64_t lead_ns() const noexcept { return m_lead_ns.load(std::memory_order_relaxed); }

 private:
  std::atomic<std::int64_t> m_lead_ns{0};
  std::int64_t m_last_ns = 0;
  bool m_started = false;
};

}  // namespace vt
