#include "vt/scene/taxel_pitch.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

namespace vt {
namespace {

// The period (pixels, sub-pixel) of the cell boundaries along one axis: the mean absolute step
// between neighbouring rows (or columns) peaks at every boundary; its autocorrelation's first
// clear peak is the period. 0 when there is none.
double boundaryPeriod_px(const ImageF& map, bool alongRows) {
  const int n = alongRows ? map.height : map.width, m = alongRows ? map.width : map.height;
  if (n < 16 || m < 1) return 0.0;
  std::vector<double> step(std::size_t(n - 1), 0.0);
  for (int i = 0; i + 1 < n; ++i) {
    double sum = 0.0;
    for (int j = 0; j < m; ++j) {
      sum += alongRows ? std::abs(map.at(j, i + 1) - map.at(j, i)) : std::abs(map.at(i + 1, j) - map.at(i, j));
    }
    step[std::size_t(i)] = sum / double(m);
  }
  double mean = 0.0;
  for (double s : step) mean += s;
  mean /= double(step.size());
  for (double& s : step) s -= mean;
  const int maxLag = std::min(40, int(step.size()) / 4);
  std::vector<double> r(std::size_t(maxLag + 2), 0.0);
  for (int lag = 0; lag <= maxLag + 1; ++lag) {
    for (std::size_t i = 0; i + std::size_t(lag) < step.size(); ++i) r[std::size_t(lag)] += step[i] * step[i + std::size_t(lag)];
  }
  if (!(r[0] > 0.0)) return 0.0;
  for (int lag = 2; lag <= maxLag; ++lag) {
    const double a = r[std::size_t(lag - 1)], b = r[std::size_t(lag)], c = r[std::size_t(lag + 1)];
    if (b > a && b >= c && b > 0.15 * r[0]) {
      const double denom = a - 2.0 * b + c;
      return double(lag) + (denom != 0.0 ? 0.5 * (a - c) / denom : 0.0);
    }
  }
  return 0.0;
}

}  // namespace

double estimateMmPerPixel(const ImageF& map, double lineSpacing_mm) {
  // The lines may run along either axis: the longer boundary period is the line spacing (the
  // shorter one, half of it, is the 1 mm taxel pitch along a line).
  const double rows = boundaryPeriod_px(map, true), cols = boundaryPeriod_px(map, false);
  const double period = std::max(rows, cols);
  return period > 0.0 ? lineSpacing_mm / period : 0.0;
}

}  // namespace vt
