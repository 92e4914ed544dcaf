#include "vt/haptics/tick_histogram.hpp"

#include <algorithm>
#include <cmath>

namespace vt::haptics {

void TickHistogram::add(std::uint32_t ns) noexcept {
  auto& bin = m_bins[std::min<std::size_t>(ns / 1000u, kBins - 1)];
  bin.store(bin.load(std::memory_order_relaxed) + 1, std::memory_order_relaxed);
  if (ns > m_max_ns.load(std::memory_order_relaxed)) m_max_ns.store(ns, std::memory_order_relaxed);
  m_count.store(m_count.load(std::memory_order_relaxed) + 1, std::memory_order_release);
}

double TickHistogram::percentile_us(double p) const noexcept {
  const std::uint64_t n = count();
  if (n == 0) return 0.0;
  // Bins read while the writer goes on may hold a few ticks more than n: the rank still lands.
  const auto rank = std::uint64_t(std::min(double(n - 1), std::floor(p * double(n))));
  std::uint64_t seen = 0;
  for (int i = 0; i < kBins - 1; ++i) {
    seen += m_bins[std::size_t(i)].load(std::memory_order_relaxed);
    if (seen > rank) return double(i + 1);
  }
  return max_us();
}

}  // namespace vt::haptics
