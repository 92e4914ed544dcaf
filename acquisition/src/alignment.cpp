#include "vt/acquisition/alignment.hpp"

#include <algorithm>
#include <cmath>

#include "vt/core/budgets.hpp"
#include "vt/core/error.hpp"

namespace vt::acq {
namespace {

std::size_t argminAbs(const std::vector<std::array<double, 3>>& v, int axis, double target) {
  std::size_t best = 0;
  double bestDist = std::abs(v[0][std::size_t(axis)] - target);
  for (std::size_t i = 1; i < v.size(); ++i) {
    const double d = std::abs(v[i][std::size_t(axis)] - target);
    if (d < bestDist) best = i, bestDist = d;
  }
  return best;
}

// Nearest sample in a sorted time series (ties go to the earlier sample, as argmin does).
std::size_t nearestTime(const std::vector<double>& t, double target, double offset) {
  const auto it = std::lower_bound(t.begin(), t.end(), target - offset);
  std::size_t j = std::size_t(it - t.begin());
  if (j == t.size()) return j - 1;
  if (j > 0 && std::abs(t[j - 1] + offset - target) <= std::abs(t[j] + offset - target)) --j;
  return j;
}

// The robot stands still until it has left its first position by more than this (4 x the
// repeatability of an industrial arm's position readout): the stationary window of a pass.
constexpr double kRestThreshold_m = 2e-5;

// Accelerometer readings [jFrom, jTo) while the robot rests: before the first robot sample that
// left the pass's first position (`forward`) or after the last one that left its last position.
// Two robot samples are kept off the motion: the robot may start between two samples, and the
// last sample within the threshold may already be moving.
void restWindow(const PassSeries& robot, const PassSeries& accel, std::size_t along, double offset, bool forward,
                PassFit& fit, int accelAxis) {
  const std::size_t n = robot.t_s.size();
  const auto at = [&](std::size_t k) { return forward ? k : n - 1 - k; };
  const double home = robot.v[at(0)][along];
  std::size_t still = 0;  // robot samples at rest from that end
  while (still < n && std::abs(robot.v[at(still)][along] - home) <= kRestThreshold_m) ++still;
  if (still < 4 || still == n) return;  // no rest run that ends before the motion
  const double tFar = robot.t_s[at(0)], tNear = robot.t_s[at(still - 3)];
  const double lo = std::min(tFar, tNear) - offset, hi = std::max(tFar, tNear) - offset;
  const auto first = std::lower_bound(accel.t_s.begin(), accel.t_s.end(), lo);
  const auto last = std::upper_bound(first, accel.t_s.end(), hi);
  const auto count = std::size_t(last - first);
  if (count < 2) return;
  const auto j0 = std::size_t(first - accel.t_s.begin());
  const auto axis = std::size_t(accelAxis);
  double mean = 0;
  for (std::size_t j = j0; j < j0 + count; ++j) mean += accel.v[j][axis];
  mean /= double(count);
  for (std::size_t j = j0; j < j0 + count; ++j) fit.restSumSq_g2 += (accel.v[j][axis] - mean) * (accel.v[j][axis] - mean);
  fit.restSamples += count;
  fit.restDof += count - 1;
}

}  // namespace

PassFit fitPass(const PassSeries& robot, const PassSeries& accel, const ScanConfig& config, const std::string& source,
                std::size_t pass, std::vector<PlacedSample>& out, const LineGeometry& geometry) {
  const auto noPhase = [&](auto&&... why) {
    fail(source, ": pass ", pass, " has no constant-velocity phase: ", why...);
  };
  const bool reference = config.compat == Compat::Reference;
  const auto along = std::size_t(geometry.axis), across = 1 - along;
  const char* axisName = along == 1 ? "Y" : "X";
  const std::size_t n = robot.t_s.size();
  if (n < std::size_t(config.minWindowSamples)) noPhase("only ", n, " robot samples");
  if (accel.t_s.empty()) fail(source, ": pass ", pass, " has no accelerometer samples");

  PassFit fit;
  double ySum = 0, xSum = 0, yMin = robot.v[0][along], yMax = robot.v[0][along];
  for (const auto& p : robot.v) {
    xSum += p[across], ySum += p[along];
    yMin = std::min(yMin, p[along]), yMax = std::max(yMax, p[along]);
  }
  const double yBar = ySum / double(n);
  fit.x_m = xSum / double(n);
  fit.travel_m = yMax - yMin;
  if (fit.travel_m < config.taxelSize_m) noPhase("the stylus travels only ", fit.travel_m * 1e3, " mm along ", axisName);

  // The window's ends in space; in time the earlier one is i1 (passes in -Y swap them). The
  // authors' code takes the travel of the line's first pass and then drops 2 robot samples
  // at each end of the window.
  const double l = reference ? geometry.moveLength_m : fit.travel_m;
  const std::size_t ia = argminAbs(robot.v, int(along), yBar - config.windowW * l);
  const std::size_t ib = argminAbs(robot.v, int(along), yBar + config.windowW * l);
  fit.i1 = std::min(ia, ib), fit.i2 = std::max(ia, ib);
  if (reference) {
    if (fit.i2 < fit.i1 + 4) noPhase("only ", fit.i2 - fit.i1 + 1, " robot samples in the window");
    fit.i1 += 2, fit.i2 -= 2;
  }
  const std::size_t count = fit.i2 - fit.i1 + 1;
  if (count < std::size_t(config.minWindowSamples)) noPhase("only ", count, " robot samples in the window");

  // Least squares along = m t + b, with t centred for conditioning.
  double tMean = 0, yMean = 0;
  for (std::size_t i = fit.i1; i <= fit.i2; ++i) tMean += robot.t_s[i], yMean += robot.v[i][along];
  tMean /= double(count), yMean /= double(count);
  double stt = 0, sty = 0;
  for (std::size_t i = fit.i1; i <= fit.i2; ++i) {
    const double dt = robot.t_s[i] - tMean;
    stt += dt * dt, sty += dt * (robot.v[i][along] - yMean);
  }
  fit.slope_m_per_s = sty / stt;
  fit.intercept_m = yMean - fit.slope_m_per_s * tMean;
  for (std::size_t i = fit.i1; i <= fit.i2; ++i) {
    const double r = robot.v[i][along] - (fit.slope_m_per_s * robot.t_s[i] + fit.intercept_m);
    fit.maxResidual_m = std::max(fit.maxResidual_m, std::abs(r));
  }
  if (fit.maxResidual_m > config.maxFitResidual_m) {
    noPhase("the robot's ", axisName, " deviates up to ", fit.maxResidual_m * 1e3, " mm from a straight-line fit (limit ",
            config.maxFitResidual_m * 1e3, " mm; max_fit_residual_m)");
  }

  // Both logs must be on one clock: the accelerometer has to cover the robot's window.
  const double offset = config.accelClockOffset_s;
  const double tStart = robot.t_s[fit.i1], tEnd = robot.t_s[fit.i2];
  const double aStart = accel.t_s.front() + offset, aEnd = accel.t_s.back() + offset;
  if (aStart > tStart || aEnd < tEnd) {
    fail(source, ": pass ", pass, ": mismatched clocks: the robot's constant-velocity window is t_s=[", tStart, ", ",
         tEnd, "] but the accelerometer covers [", aStart, ", ", aEnd,
         "] on the robot clock (check accel_clock_offset_s)");
  }
  const std::size_t jStart = nearestTime(accel.t_s, tStart, offset);
  const std::size_t jEnd = nearestTime(accel.t_s, tEnd, offset);
  // The authors' code keeps the nearest samples themselves (no +1 / -1).
  const std::size_t trimStart = reference ? 0 : std::size_t(config.accelTrimStart);
  const std::size_t trimEnd = reference ? 0 : std::size_t(config.accelTrimEnd);
  if (jEnd < trimEnd || jStart + trimStart + trimEnd > jEnd) {
    fail(source, ": pass ", pass, ": no accelerometer samples inside the constant-velocity window");
  }
  fit.j1 = jStart + trimStart;
  fit.j2 = jEnd - trimEnd;
  restWindow(robot, accel, along, offset, true, fit, config.accelAxis);
  restWindow(robot, accel, along, offset, false, fit, config.accelAxis);
  const auto axis = std::size_t(config.accelAxis);
  for (std::size_t j = fit.j1; j <= fit.j2; ++j) {
    const double t = accel.t_s[j] + offset, a = accel.v[j][axis] - config.gravity_g;
    out.push_back({fit.slope_m_per_s * t + fit.intercept_m, std::abs(a), float(a), t});
  }
  return fit;
}

namespace {

// Sums of V, V^2 and V^4 over a bin's samples, in all and over alternate samples.
struct Moments {
  struct Sums {
    double v = 0, v2 = 0, v4 = 0;
    int count = 0;
  };
  Sums all, half[2];
  int count = 0;
  void add(double x) noexcept {
    const double x2 = x * x, x4 = x2 * x2;
    for (Sums* s : {&all, &half[count & 1]}) s->v += x, s->v2 += x2, s->v4 += x4, ++s->count;
    ++count;
  }
  Taxel taxel(double x_m, double y0_m, double y1_m) const noexcept {
    const auto mean = [](const Sums& s, double Sums::*field) { return s.count ? s.*field / s.count : 0.0; };
    Taxel t{x_m, y0_m, y1_m, mean(all, &Sums::v), count, mean(all, &Sums::v2), mean(all, &Sums::v4)};
    for (int h = 0; h < 2; ++h) {
      t.halves[h] = {mean(half[h], &Sums::v), mean(half[h], &Sums::v2), mean(half[h], &Sums::v4), half[h].count};
    }
    return t;
  }
};

void sortByPosition(std::vector<PlacedSample>& pooled) {
  const auto byPosition = [](const PlacedSample& a, const PlacedSample& b) { return a.y_m < b.y_m; };
  if (!std::is_sorted(pooled.begin(), pooled.end(), byPosition)) std::sort(pooled.begin(), pooled.end(), byPosition);
}

}  // namespace

std::vector<Taxel> binTaxels(std::vector<PlacedSample>& pooled, double x_m, double taxelSize_m) {
  std::vector<Taxel> taxels;
  if (pooled.empty()) return taxels;
  sortByPosition(pooled);
  const double y0 = pooled.front().y_m;
  const double span = pooled.back().y_m - y0;
  // Whole bins only: a remainder bin a fraction of a taxel long would hold a few samples of
  // a fraction of the texture period and still be drawn (and counted) as a full taxel.
  const auto bins = std::size_t(std::max(1.0, std::round(span / taxelSize_m)));
  const double width = span > 0 ? span / double(bins) : taxelSize_m;
  std::vector<Moments> sums(bins);
  for (const PlacedSample& s : pooled) sums[std::min(bins - 1, std::size_t((s.y_m - y0) / width))].add(s.v_g);
  for (std::size_t k = 0; k < bins; ++k) {
    if (sums[k].count == 0) continue;
    const double lo = y0 + double(k) * width;
    taxels.push_back(sums[k].taxel(x_m, lo, k + 1 == bins ? y0 + span : lo + width));
  }
  return taxels;
}

std::vector<Taxel> binTaxelsReference(std::vector<PlacedSample>& pooled, double x_m, double taxelSize_m,
                                      double windowLength_m) {
  std::vector<Taxel> taxels;
  if (pooled.empty()) return taxels;
  sortByPosition(pooled);
  const double y0 = pooled.front().y_m, end = y0 + windowLength_m;
  std::size_t first = 0;  // first sample >= the bin's lower bound
  for (std::size_t k = 0; y0 + double(k) * taxelSize_m < end; ++k) {
    const double lo = y0 + double(k) * taxelSize_m, hi = lo + taxelSize_m;
    while (first < pooled.size() && pooled[first].y_m < lo) ++first;
    Moments sums;
    for (std::size_t i = first; i < pooled.size() && pooled[i].y_m <= hi; ++i) sums.add(pooled[i].v_g);
    if (sums.count == 0) break;
    taxels.push_back(sums.taxel(x_m, lo, hi));
  }
  return taxels;
}

LineResult processLine(const LineLogs& logs, const ScanConfig& config, const std::string& source, int axis) {
  LineBuffers buffers;
  return processLine(logs, config, source, axis, buffers, true);
}

LineResult processLine(const LineLogs& logs, const ScanConfig& config, const std::string& source, int axis,
                       LineBuffers& buffers, bool keepSamples) {
  LineResult line;
  line.axis = axis;
  LineGeometry geometry{axis, 0.0};
  if (!logs.robot.empty() && !logs.robot[0].v.empty()) {
    // run.py's aubo_x: the mean X of the first pass without its first and last 100 samples.
    const auto& first = logs.robot[0].v;
    const std::size_t lo = first.size() > 200 ? 100 : 0, hi = first.size() > 200 ? first.size() - 100 : first.size();
    double sum = 0;
    for (std::size_t i = lo; i < hi; ++i) sum += first[i][std::size_t(1 - axis)];
    line.firstPassX_m = sum / double(hi - lo);
    // The authors' move length: last minus first position of the first pass (its sign dropped,
    // or a first pass towards -Y would leave no bins at all).
    geometry.moveLength_m = std::abs(logs.robot[0].v.back()[std::size_t(axis)] - logs.robot[0].v.front()[std::size_t(axis)]);
  }
  std::vector<PlacedSample>& pooled = buffers.pooled;
  pooled.clear();
  std::size_t accelRows = 0;  // an upper bound of the samples placed: at most one allocation per line
  for (const PassSeries& pass : logs.accel) accelRows += pass.t_s.size();
  pooled.reserve(accelRows);
  double xSum = 0;
  std::vector<std::size_t> runStarts;
  for (std::size_t p = 0; p < logs.robot.size(); ++p) {
    runStarts.push_back(pooled.size());
    line.passes.push_back(fitPass(logs.robot[p], logs.accel[p], config, source, p, pooled, geometry));
    xSum += line.passes.back().x_m;
    if (p == 0 && keepSamples) line.firstPass.assign(pooled.begin(), pooled.end());  // in time order
    // y = m t + b over increasing t: each pass is one monotonic run; make it ascending.
    if (line.passes.back().slope_m_per_s < 0) std::reverse(pooled.begin() + long(runStarts.back()), pooled.end());
  }
  // Sorting by position = merging the sorted runs pairwise, level by level, between the two
  // buffers (O(n log passes); stable, as one sort of the pooled samples would be).
  runStarts.push_back(pooled.size());
  if (runStarts.size() > 2 && buffers.merged.size() < pooled.size()) buffers.merged.resize(pooled.size());
  std::vector<PlacedSample>* from = &pooled;
  std::vector<PlacedSample>* to = &buffers.merged;
  const auto byPosition = [](const PlacedSample& a, const PlacedSample& b) { return a.y_m < b.y_m; };
  while (runStarts.size() > 2) {
    std::size_t merged = 0;  // runs after this level
    for (std::size_t r = 0; r + 1 < runStarts.size(); r += 2, ++merged) {
      const auto at = [&](std::vector<PlacedSample>* v, std::size_t k) { return v->begin() + long(runStarts[k]); };
      if (r + 2 < runStarts.size()) {
        std::merge(at(from, r), at(from, r + 1), at(from, r + 1), at(from, r + 2), at(to, r), byPosition);
      } else {
        std::copy(at(from, r), at(from, r + 1), at(to, r));  // an odd run out waits for the next level
      }
      runStarts[merged] = runStarts[r];
    }
    runStarts[merged] = runStarts.back();
    runStarts.resize(merged + 1);
    std::swap(from, to);
  }
  if (from != &pooled) {
    const std::size_t n = pooled.size();
    pooled.swap(buffers.merged);
    pooled.resize(n);
  }
  line.x_m = xSum / double(line.passes.size());
  // Bins are allocated by span / taxel size: a log whose position runs away must not size them.
  if (!pooled.empty() && (pooled.back().y_m - pooled.front().y_m) / config.taxelSize_m > budget::kTaxelsPerLine) {
    fail(source, ": the stylus covers ", (pooled.back().y_m - pooled.front().y_m), " m along the scan line, over the limit of ",
         budget::kTaxelsPerLine, " taxels of ", config.taxelSize_m, " m per scan line (docs/RELIABILITY.md)");
  }
  line.taxels = config.compat == Compat::Reference
                    ? binTaxelsReference(pooled, line.x_m, config.taxelSize_m, 2 * config.windowW * geometry.moveLength_m)
                    : binTaxels(pooled, line.x_m, config.taxelSize_m);
  return line;
}

}  // namespace vt::acq
