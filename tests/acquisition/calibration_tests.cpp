#include <catch2/catch.hpp>

#include <random>

#include "scan_fixture.hpp"
#include "vt/acquisition/calibration.hpp"
#include "vt/core/error.hpp"

using namespace vt::acq;

namespace {

std::vector<Correspondence> markedPoints(const SyntheticTruth& truth, int n, double noise_px, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> click(0.0, noise_px);
  std::vector<Correspondence> pts;
  const double x0 = truth.lineX_m.front() - 0.003, x1 = truth.lineX_m.back() + 0.003;
  const double y0 = truth.windowY0_m - 0.003, y1 = truth.windowY1_m + 0.003;
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) {
      const double x = x0 + (x1 - x0) * i / (n - 1), y = y0 + (y1 - y0) * j / (n - 1);
      const glm::dvec2 p = truth.camera.project(x, y);
      pts.push_back({x, y, p.x + click(rng), p.y + click(rng)});
    }
  }
  return pts;
}

// Largest |f_calibrated(P) - f_true(P)| over a dense grid of the scanned area.
double worldToPixelError(const SyntheticTruth& truth, const CameraModel& fitted) {
  double worst = 0;
  const double x0 = truth.lineX_m.front(), x1 = truth.lineX_m.back();
  for (int i = 0; i <= 40; ++i) {
    for (int j = 0; j <= 40; ++j) {
      const double x = x0 + (x1 - x0) * i / 40, y = truth.windowY0_m + (truth.windowY1_m - truth.windowY0_m) * j / 40;
      worst = std::max(worst, glm::length(fitted.project(x, y) - truth.camera.project(x, y)));
    }
  }
  return worst;
}

}  // namespace

TEST_CASE("rodrigues round trip") {
  const std::array<double, 3> r{0.3, -1.2, 0.7};
  const auto back = vectorFromRotation(rotationFromVector(r));
  for (int i = 0; i < 3; ++i) CHECK(back[std::size_t(i)] == Approx(r[std::size_t(i)]).margin(1e-12));
}

TEST_CASE("calibration recovers the synthetic camera within a pixel over the scanned area") {
  for (const bool large : {false, true}) {
    SyntheticOptions o = test::smallOptions();
    if (large) o.scanLength_m = 0.1, o.lines = 50, o.photoWidth = 640, o.photoHeight = 480;
    const SyntheticTruth truth = makeSyntheticTruth(o);
    const auto pts = markedPoints(truth, 5, 0.15, 3);
    const CalibrationResult r = calibrateCamera(pts, o.photoWidth, o.photoHeight, 1e-3, "test");
    INFO("large scan " << large << " rms " << r.rmsError_px << " iterations " << r.iterations);
    CHECK(r.converged);
    CHECK(r.rmsError_px < 0.5);
    CHECK(r.maxError_px < 1.0);
    CHECK(worldToPixelError(truth, r.camera) < 1.0);
    // Exact clicks: the fit must explain them almost perfectly.
    const CalibrationResult exact = calibrateCamera(markedPoints(truth, 5, 0.0, 3), o.photoWidth, o.photoHeight, 1e-3, "t");
    CHECK(exact.rmsError_px < 0.02);
    CHECK(worldToPixelError(truth, exact.camera) < 0.1);
  }
}

TEST_CASE("calibration with the minimum of eight points still maps the area") {
  const SyntheticTruth truth = makeSyntheticTruth(test::smallOptions());
  auto pts = markedPoints(truth, 3, 0.1, 5);
  pts.pop_back();  // 8 points
  const CalibrationResult r = calibrateCamera(pts, 320, 240, 1e-3, "test");
  CHECK(r.rmsError_px < 0.5);
  CHECK(worldToPixelError(truth, r.camera) < 1.5);
}

TEST_CASE("calibration rejects too few or collinear points") {
  const SyntheticTruth truth = makeSyntheticTruth(test::smallOptions());
  auto pts = markedPoints(truth, 3, 0.0, 5);
  pts.resize(7);
  CHECK_THROWS_WITH(calibrateCamera(pts, 320, 240, 1e-3, "calib.csv"),
                    Catch::Contains("calib.csv") && Catch::Contains("too few calibration points: 7"));
  std::vector<Correspondence> line;
  for (int i = 0; i < 10; ++i) line.push_back({0.3 + 0.01 * i, 0.0, 10.0 * i, 5.0});
  CHECK_THROWS_WITH(calibrateCamera(line, 320, 240, 1e-3, "calib.csv"), Catch::Contains("collinear"));
}
