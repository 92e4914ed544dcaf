#include "vt/core/clock.hpp"

#include <chrono>
#include <thread>

namespace vt {

std::int64_t SteadyClock::now_ns() const noexcept {
  return std::chrono::duration_cast<std::chrono::nanoseconds>(
             std::chrono::steady_clock::now().time_since_epoch())
      .count();
}

void SteadyClock::sleepUntil(std::int64_t deadline_ns) const noexcept {
  // The OS wakes us up to ~60 us late; sleep to just before the deadline, then spin.
  constexpr std::int64_t kSpinWindow_ns = 80'000;
  std::int64_t remaining = deadline_ns - now_ns();
  if (remaining > kSpinWindow_ns) {
    std::this_thread::sleep_for(std::chrono::nanoseconds(remaining - kSpinWindow_ns));
  }
  while (now_ns() < deadline_ns) {
    std::this_thread::yield();
  }
}

void SteadyClock::spinUntil(std::int64_t deadline_ns) const noexcept {
  while (now_ns() < deadline_ns) {
    // A spin-wait hint: the core stays awake without starving its sibling hyperthread.
#if defined(__x86_64__) || defined(__i386__)
    __builtin_ia32_pause();
#elif defined(__aarch64__)
    asm volatile("yield");
#endif
  }
}

const SteadyClock& SteadyClock::instance() noexcept {
  static const SteadyClock clock;
  return clock;
}

void ManualClock::sleepUntil(std::int64_t deadline_ns) const noexcept {
  std::int64_t now = m_now_ns.load();
  while (now < deadline_ns && !m_now_ns.compare_exchange_weak(now, deadline_ns)) {
  }
}

}  // namespace vt
