#pragma once
// How fast a counter grew lately: the HUD shows overruns and stale poses as a rate over the
// last few seconds, so a panel opened after an hour says what happens now, not what happened
// once at start-up.
#include <cstdint>
#include <deque>
#include <utility>

namespace vt::ui {

/// The rate of a growing total over a sliding window. One thread (the HUD's).
class RecentRate {
 public:
  /// Over the last `window_s` seconds, from samples at least `spacing_s` apart.
  explicit RecentRate(double window_s = 5.0, double spacing_s = 0.1) noexcept;
  /// Adds the counter's total at t_ns and returns its growth per second over the window (0 with
  /// less than two samples; a total that went down, a restarted counter, starts the window anew).
  double update(std::int64_t t_ns, std::uint64_t total);

 private:
  std::int64_t m_window_ns, m_spacing_ns;
  std::deque<std::pair<std::int64_t, std::uint64_t>> m_samples;  // oldest first
};

}  // namespace vt::ui
