#pragma once
// Taxel to world (the paper's Sec. III): per pass, a constant-velocity fit of the robot's Y
// over the central window gives every accelerometer sample a position; the passes of a
// line are pooled and averaged into one taxel per bin. Pure functions, any thread.
#include <cstddef>
#include <string>
#include <vector>

#include "vt/acquisition/scan.hpp"

namespace vt::acq {

/// The constant-velocity fit of one pass: Y = slope * t + intercept over robot samples i1..i2.
struct PassFit {
  std::size_t i1 = 0, i2 = 0;  // robot window (inclusive), i1 earlier in time
  std::size_t j1 = 0, j2 = 0;  // accelerometer window (inclusive)
  double slope_m_per_s = 0;
  double intercept_m = 0;
  double x_m = 0;              // mean X of the pass
  double travel_m = 0;         // l: max(Y) - min(Y)
  double maxResidual_m = 0;    // largest |Y_i - fit| inside the window
};

/// One accelerometer sample placed on the object: position along the line and V = |a - g0|.
struct PlacedSample {
  double y_m;
  double v_g;
};

/// Fits pass `pass` and appends its placed samples to `out`. Throws vt::Error naming `source`
/// when the pass has no constant-velocity phase or the clocks do not overlap.
PassFit fitPass(const PassSeries& robot, const PassSeries& accel, const ScanConfig& config, const std::string& source,
                std::size_t pass, std::vector<PlacedSample>& out);

/// One taxel: a bin of the line [y0, y1) at X, with the mean vibration intensity of its samples.
struct Taxel {
  double x_m = 0;
  double y0_m = 0, y1_m = 0;
  double v_g = 0;
  int samples = 0;
};

/// All passes of a line fitted, pooled, sorted and binned.
struct LineResult {
  double x_m = 0;
  std::vector<PassFit> passes;
  std::vector<Taxel> taxels;
};

/// Sorts the pooled samples by position and averages V in bins of config.taxelSize_m starting
/// at the smallest position (as the paper's code); empty bins give no taxel.
std::vector<Taxel> binTaxels(std::vector<PlacedSample>& pooled, double x_m, double taxelSize_m);

/// Processes one line's logs; `source` names the line's files in errors.
LineResult processLine(const LineLogs& logs, const ScanConfig& config, const std::string& source);

}  // namespace vt::acq
