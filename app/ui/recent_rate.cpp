#include "ui/recent_rate.hpp"

namespace vt::ui {

RecentRate::RecentRate(double window_s, double spacing_s) noexcept
    : m_window_ns(std::int64_t(window_s * 1e9)), m_spacing_ns(std::int64_t(spacing_s * 1e9)) {}

double RecentRate::update(std::int64_t t_ns, std::uint64_t total) {
  if (!m_samples.empty() && (total < m_samples.back().second || t_ns < m_samples.back().first)) m_samples.clear();
  if (m_samples.empty() || t_ns - m_samples.back().first >= m_spacing_ns) m_samples.emplace_back(t_ns, total);
  // Keep one sample at or before the window's start, so the rate covers the whole window.
  while (m_samples.size() > 2 && m_samples[1].first <= t_ns - m_window_ns) m_samples.pop_front();
  const auto& [t0, total0] = m_samples.front();
  if (t_ns <= t0) return 0.0;
  return double(total - total0) / (double(t_ns - t0) * 1e-9);
}

}  // namespace vt::ui
