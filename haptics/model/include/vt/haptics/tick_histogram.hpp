#pragma once
// Tick durations over a whole run in 1 us bins: percentiles of every tick since the loop began,
// where LoopStats' recent-tick window sees only the last few thousand. One writer (the ticking
// thread: no locks, no allocation), any number of readers.
#include <array>
#include <atomic>
#include <cstdint>

namespace vt::haptics {

class TickHistogram {
 public:
  /// Bins of 1 us; a tick of kBins - 1 us or longer counts in the last one.
  static constexpr int kBins = 1024;

  /// The ticking thread only.
  void add(std::uint32_t ns) noexcept;
  /// Ticks counted. Any thread.
  std::uint64_t count() const noexcept { return m_count.load(std::memory_order_acquire); }
  /// The upper edge (us) of the bin holding the tick at rank floor(p * count), the same rank
  /// LoopStats' window percentiles use: the p-th tick took less than this, to 1 us. The longest
  /// tick's own time when that falls in the last bin; 0 before the first tick. Any thread.
  double percentile_us(double p) const noexcept;
  /// The longest tick (us). Any thread.
  double max_us() const noexcept { return double(m_max_ns.load(std::memory_order_relaxed)) / 1000.0; }

 private:
  std::array<std::atomic<std::uint64_t>, kBins> m_bins{};
  std::atomic<std::uint64_t> m_count{0};
  std::atomic<std::uint32_t> m_max_ns{0};
};

}  // namespace vt::haptics
