#pragma once
// Frame-time figures the render paths print (vtouching render, the desktop preview with --frames).
#include <vector>

namespace vt::app {

/// Mean, 95th and 99th percentile of frame times (milliseconds); zero when there are none.
struct FrameStats {
  double mean_ms = 0.0;
  double p95_ms = 0.0;
  double p99_ms = 0.0;
};

/// Summarises the frame times (milliseconds).
FrameStats summarizeFrameTimes(std::vector<double> times_ms);

}  // namespace vt::app
