#include "modes/frame_stats.hpp"

#include <algorithm>

namespace vt::app {

FrameStats summarizeFrameTimes(std::vector<double> times_ms) {
  FrameStats s;
  if (times_ms.empty()) return s;
  for (double t : times_ms) s.mean_ms += t;
  s.mean_ms /= double(times_ms.size());
  std::sort(times_ms.begin(), times_ms.end());
  auto percentile = [&](double q) { return times_ms[std::min(times_ms.size() - 1, std::size_t(q * double(times_ms.size())))]; };
  s.p95_ms = percentile(0.95);
  s.p99_ms = percentile(0.99);
  return s;
}

}  // namespace vt::app
