#include "modes/frame_stats.hpp"

#include <algorithm>

namespace vt::app {

FrameStats summarizeFrameTimes(std::vector<double> times_ms) {
  FrameStats s;
  if (times_ms.empty()) return s;
  for (double t : times_ms) s.mean_ms += t;
  s.mean_ms /= double(times_ms.size());
  std::sort(times_ms.begin(), times_ms.end());
  s.p95_ms = times_ms[std::min(times_ms.size() - 1, std::size_t(0.95 * double(times_ms.size())))];
  return s;
}

}  // namespace vt::app
