#include <catch2/catch.hpp>

#include <cmath>
#include <fstream>

#include <nlohmann/json.hpp>

#include "scan_fixture.hpp"
#include "vt/acquisition/pipeline.hpp"
#include "vt/core/error.hpp"

using namespace vt::acq;

namespace {

double pearson(const std::vector<double>& a, const std::vector<double>& b) {
  const double n = double(a.size());
  double ma = 0, mb = 0;
  for (std::size_t i = 0; i < a.size(); ++i) ma += a[i], mb += b[i];
  ma /= n, mb /= n;
  double sab = 0, saa = 0, sbb = 0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    sab += (a[i] - ma) * (b[i] - mb), saa += (a[i] - ma) * (a[i] - ma), sbb += (b[i] - mb) * (b[i] - mb);
  }
  return sab / std::sqrt(saa * sbb);
}

// The ground truth at the scanner's resolution: the field along the nearest scan line,
// averaged over one taxel (1 mm) around y. Finer detail between lines is not measured.
double sampledTruth(const SyntheticTruth& truth, double x, double y) {
  const double spacing = truth.options.lineSpacing_m;
  const auto line = std::clamp(std::lround((x - truth.lineX_m.front()) / spacing), 0L, long(truth.lineX_m.size()) - 1);
  double sum = 0;
  for (int k = 0; k < 9; ++k) sum += truth.vibration_g(truth.lineX_m[std::size_t(line)], y + (k - 4) * 0.125e-3);
  return sum / 9;
}

// Map vs ground truth at world points of the scanned area, located in the final image
// through the true camera (not the calibrated one) and the scan's warp and crop.
double mapCorrelation(const SyntheticTruth& truth, const AcquireResult& r, std::size_t* used = nullptr) {
  std::vector<double> map, gt;
  const double spacing = truth.options.lineSpacing_m;
  const double x0 = truth.lineX_m.front() - 0.5 * spacing, x1 = truth.lineX_m.back() + 0.5 * spacing;
  for (double x = x0 + 0.1e-3; x < x1; x += 0.25e-3) {
    for (double y = truth.windowY0_m + 0.1e-3; y < truth.windowY1_m; y += 0.25e-3) {
      const glm::dvec2 p = applyHomography(r.photoToOutput, truth.camera.project(x, y));
      const int px = int(std::lround(p.x)), py = int(std::lround(p.y));
      if (px < 0 || py < 0 || px >= r.map.value_g.width || py >= r.map.value_g.height) continue;
      if (!r.map.coverage.at(px, py)) continue;
      map.push_back(r.map.value_g.at(px, py));
      gt.push_back(sampledTruth(truth, x, y));
    }
  }
  if (used) *used = map.size();
  return pearson(map, gt);
}

}  // namespace

TEST_CASE("map correlates with the ground-truth vibration field for every textured kind") {
  for (auto name : syntheticKindNames()) {
    const SyntheticKind kind = parseSyntheticKind(name);
    if (kind == SyntheticKind::SmoothCeramicTile) continue;  // no structure to correlate: noise only
    SyntheticOptions o = test::smallOptions(kind);
    o.scanLength_m = 0.04, o.lines = 16;
    const auto scan = test::writeScan(std::string("corr_") + std::string(name), o);
    const AcquireResult r = acquire(loadScan(scan.dir));
    std::size_t used = 0;
    const double rho = mapCorrelation(scan.truth, r, &used);
    INFO(name << ": pearson " << rho << " over " << used << " points");
    CHECK(used > 10000);
    CHECK(rho >= 0.9);
  }
}
