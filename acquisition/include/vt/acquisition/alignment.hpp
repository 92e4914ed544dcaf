#pragma once
// Taxel to world (the paper's Sec. III): per pass, a constant-velocity fit of the robot's
// position along the scan axis (Y in the paper; X for the across passes) over the central
// window gives every accelerometer sample a position; the passes of a line are pooled and
// averaged into one taxel per bin. "Along" is the scan axis, "across" the other robot axis.
// Pure functions, any thread.
#include <array>
#include <cstddef>
#include <string>
#include <vector>

#include "vt/acquisition/scan.hpp"

namespace vt::acq {

/// The constant-velocity fit of one pass: along = slope * t + intercept over robot samples i1..i2.
struct PassFit {
  std::size_t i1 = 0, i2 = 0;  // robot window (inclusive), i1 earlier in time
  std::size_t j1 = 0, j2 = 0;  // accelerometer window (inclusive)
  double slope_m_per_s = 0;
  double intercept_m = 0;
  double x_m = 0;              // mean across coordinate of the pass (X for Y passes)
  double travel_m = 0;         // l: max - min along the scan axis
  double maxResidual_m = 0;    // largest |along_i - fit| inside the window
  // Accelerometer readings while the robot stood still before and after the pass (the noise
  // floor, vt/acquisition/noise.hpp): how many, their degrees of freedom (each rest run's own mean
  // removed) and their squared deviations from those means.
  std::size_t restSamples = 0, restDof = 0;
  double restSumSq_g2 = 0;
};

/// One accelerometer sample placed on the object: position along the line, V = |a - g0|, and
/// the signed acceleration a - g0 with its time on the robot clock (for measured waveforms).
struct PlacedSample {
  double y_m;
  double v_g;
  float a_g = 0.0f;
  double t_s = 0.0;
};

/// What a pass fit needs besides the config: the robot axis the passes move along (0 = X,
/// 1 = Y) and, for Compat::Reference, the line's move length taken from its first pass.
struct LineGeometry {
  int axis = 1;
  double moveLength_m = 0.0;
};

/// Fits pass `pass` and appends its placed samples to `out`. Throws vt::Error naming `source`
/// when the pass has no constant-velocity phase or the clocks do not overlap.
PassFit fitPass(const PassSeries& robot, const PassSeries& accel, const ScanConfig& config, const std::string& source,
                std::size_t pass, std::vector<PlacedSample>& out, const LineGeometry& geometry = {});

/// One taxel: a bin [y0, y1) along the line at across position x, with the mean vibration
/// intensity of its samples (x is the robot's X for Y passes, its Y for X passes).
struct Taxel {
  double x_m = 0;
  double y0_m = 0, y1_m = 0;
  double v_g = 0;
  int samples = 0;
  double m2_g2 = 0, m4_g4 = 0;  // mean V^2 and V^4 of its samples (for the noise correction)
  /// The same three means over each half of its samples (alternate samples in position order):
  /// how far the two disagree measures the taxel value's own noise.
  struct Half {
    double v_g = 0, m2_g2 = 0, m4_g4 = 0;
    int samples = 0;
  };
  Half halves[2];
};

/// All passes of a line fitted, pooled, sorted and binned.
struct LineResult {
  double x_m = 0;   // across position
  double firstPassX_m = 0;  // the authors' across position: pass 0's robot samples 100 .. n - 100 (all if fewer)
  int axis = 1;     // robot axis the passes move along (0 = X, 1 = Y)
  std::vector<PassFit> passes;
  std::vector<Taxel> taxels;
  std::vector<PlacedSample> firstPass;  // pass 0's placed samples in time order (kept for waveforms)

  /// Robot (X, Y) of a point of this line given its position along the line.
  std::array<double, 2> world(double along_m) const noexcept {
    return axis == 1 ? std::array<double, 2>{x_m, along_m} : std::array<double, 2>{along_m, x_m};
  }
};

/// Sorts the pooled samples by position and averages V in whole bins: the measured span
/// [smallest, largest position] is cut into n = max(1, round(span / taxelSize_m)) equal bins,
/// so every bin is within half a bin of the nominal size and none is a sliver; empty bins give
/// no taxel.
std::vector<Taxel> binTaxels(std::vector<PlacedSample>& pooled, double x_m, double taxelSize_m);

/// The authors' code: bins of taxelSize_m from the smallest position over windowLength_m,
/// each inclusive at both ends (a sample on a boundary counts in both), stopping at the first
/// empty bin.
std::vector<Taxel> binTaxelsReference(std::vector<PlacedSample>& pooled, double x_m, double taxelSize_m,
                                      double windowLength_m);

/// Processes one line's logs (passes along robot `axis`, 0 = X, 1 = Y); `source` names the
/// line's files in errors.
LineResult processLine(const LineLogs& logs, const ScanConfig& config, const std::string& source, int axis = 1);

/// Storage processLine reuses from one line to the next (one per worker thread), so lines after
/// the first place and sort their samples without fresh memory.
struct LineBuffers {
  std::vector<PlacedSample> pooled, merged;
};

/// Same with `buffers`; LineResult::firstPass is filled only when keepSamples (measureWaveforms
/// cuts from it); the pooled samples stay in buffers.pooled until the next line.
LineResult processLine(const LineLogs& logs, const ScanConfig& config, const std::string& source, int axis,
                       LineBuffers& buffers, bool keepSamples);

}  // namespace vt::acq
