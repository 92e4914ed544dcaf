#include <catch2/catch.hpp>

#include <fstream>
#include <random>

#include <nlohmann/json.hpp>

#include "scan_fixture.hpp"
#include "vt/acquisition/calibration.hpp"
#include "vt/acquisition/map.hpp"
#include "vt/acquisition/pipeline.hpp"
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
    const CalibrationResult r = calibrateCamera(pts, o.photoWidth, o.photoHeight, CalibrationPriors{}, "test");
    INFO("large scan " << large << " rms " << r.rmsError_px << " iterations " << r.iterations);
    CHECK(r.converged);
    CHECK(r.rmsError_px < 0.5);
    CHECK(r.maxError_px < 1.0);
    CHECK(worldToPixelError(truth, r.camera) < 1.0);
    // Exact clicks: the fit must explain them almost perfectly.
    const CalibrationResult exact = calibrateCamera(markedPoints(truth, 5, 0.0, 3), o.photoWidth, o.photoHeight, CalibrationPriors{}, "t");
    CHECK(exact.rmsError_px < 0.02);
    CHECK(worldToPixelError(truth, exact.camera) < 0.1);
  }
}

TEST_CASE("calibration with the minimum of eight points still maps the area") {
  const SyntheticTruth truth = makeSyntheticTruth(test::smallOptions());
  auto pts = markedPoints(truth, 3, 0.1, 5);
  pts.pop_back();  // 8 points
  const CalibrationResult r = calibrateCamera(pts, 320, 240, CalibrationPriors{}, "test");
  CHECK(r.rmsError_px < 0.5);
  CHECK(worldToPixelError(truth, r.camera) < 1.5);
}

TEST_CASE("calibration rejects too few or collinear points") {
  const SyntheticTruth truth = makeSyntheticTruth(test::smallOptions());
  auto pts = markedPoints(truth, 3, 0.0, 5);
  pts.resize(7);
  CHECK_THROWS_WITH(calibrateCamera(pts, 320, 240, CalibrationPriors{}, "calib.csv"),
                    Catch::Contains("calib.csv") && Catch::Contains("too few calibration points: 7"));
  std::vector<Correspondence> line;
  for (int i = 0; i < 10; ++i) line.push_back({0.3 + 0.01 * i, 0.0, 10.0 * i, 5.0});
  CHECK_THROWS_WITH(calibrateCamera(line, 320, 240, CalibrationPriors{}, "calib.csv"), Catch::Contains("collinear"));
}

TEST_CASE("one view: every intrinsic within three of its reported standard errors of the truth") {
  // The default 640 x 480 photo, the small test photo and the wide 1920 x 1080 camera; several
  // click-noise draws each. Priors hold cx, cy and k2 where one plane cannot place them, and
  // their uncertainty reaches fx through the covariance (a fixed cx, cy, k2 biased fx by up to
  // 3.4 standard errors).
  struct Camera {
    int width, height;
    double scale_px_per_mm;
  };
  for (const Camera camera : {Camera{320, 240, 4.0}, Camera{640, 480, 2.9}, Camera{1920, 1080, 6.0}}) {
    SyntheticOptions o = test::smallOptions();
    o.scanLength_m = 0.1, o.lines = 50;
    o.photoWidth = camera.width, o.photoHeight = camera.height, o.photoScale_px_per_mm = camera.scale_px_per_mm;
    const SyntheticTruth truth = makeSyntheticTruth(o);
    const CameraModel& t = truth.camera;
    const double want[6] = {t.fx, t.fy, t.cx, t.cy, t.k1, t.k2};
    for (std::uint64_t seed = 1; seed <= 6; ++seed) {
      const CalibrationResult r = calibrateCamera(markedPoints(truth, 5, 0.15, seed), camera.width, camera.height,
                                                  CalibrationPriors{}, "test");
      const CameraModel& c = r.camera;
      const double got[6] = {c.fx, c.fy, c.cx, c.cy, c.k1, c.k2};
      for (int i = 0; i < 6; ++i) {
        INFO(camera.width << "x" << camera.height << " seed " << seed << " parameter " << i << ": " << got[i] << " +- "
                          << r.std[std::size_t(i)] << ", true " << want[i]);
        CHECK(std::abs(got[i] - want[i]) <= 3 * r.std[std::size_t(i)]);
      }
      CHECK(r.priors[2]);  // principal point and k2 carry priors; fx is the points' own
      CHECK(r.priors[5]);
      CHECK_FALSE(r.priors[0]);
      CHECK(worldToPixelError(truth, c) < 1.0);
    }
  }
}

TEST_CASE("a focal-length prior makes one view's fx reliable and close to the truth") {
  SyntheticOptions o = test::smallOptions();
  o.scanLength_m = 0.1, o.lines = 50, o.photoWidth = 640, o.photoHeight = 480;
  const SyntheticTruth truth = makeSyntheticTruth(o);
  const auto points = markedPoints(truth, 5, 0.15, 3);
  const CalibrationResult free = calibrateCamera(points, 640, 480, CalibrationPriors{}, "test");
  // A prior as a datasheet or an earlier calibration gives it: 1 % off, 1 % standard deviation.
  const double focal = truth.camera.fx * 1.01;
  const CalibrationResult r = calibrateCamera(points, 640, 480, CalibrationPriors{1e-3, std::array{focal, 0.01 * focal}}, "test");
  INFO("fx " << free.camera.fx << " +- " << free.std[0] << " free, " << r.camera.fx << " +- " << r.std[0]
             << " with the prior; true " << truth.camera.fx);
  CHECK(r.std[0] < free.std[0]);
  CHECK(std::abs(r.camera.fx - truth.camera.fx) <= 3 * r.std[0]);
  const auto report = nlohmann::json::parse(calibrationReportJson(r, points));
  CHECK(report["parameters"]["fx"]["prior"]["mean"].get<double>() == Approx(focal));
  CHECK(report["parameters"]["cx"]["reliable"] == false);
}

TEST_CASE("a camera given in scan.json is used as given and reported as such") {
  const SyntheticTruth truth = makeSyntheticTruth(test::smallOptions());
  const CameraModel& t = truth.camera;
  KnownCamera known{t.fx, t.fy, t.cx, t.cy, {t.k1, t.k2, 0.0, 0.0, 0.0}, t.rvec, t.t_m};
  const auto points = markedPoints(truth, 5, 0.0, 3);
  const CalibrationResult r = givenCamera(known, points);
  CHECK(r.given);
  CHECK(r.rmsError_px < 1e-9);
  const auto report = nlohmann::json::parse(calibrationReportJson(r, points));
  CHECK(report["parameters"]["fx"]["status"] == "given");
  // Tangential terms move the projection as OpenCV's model does: p1 shifts v by p1 (r^2 + 2 y^2).
  known.distortion[2] = 1e-2;
  const CalibrationResult tangential = givenCamera(known, points);
  CHECK(tangential.rmsError_px > 0.01);
  const glm::dvec2 pixel = tangential.camera.project(points[7].x_m, points[7].y_m);
  const glm::dvec2 back = tangential.camera.planePoint(pixel);
  CHECK(back.x == Approx(points[7].x_m).margin(1e-7));
  CHECK(back.y == Approx(points[7].y_m).margin(1e-7));
}

TEST_CASE("several target views determine the principal point and distortion") {
  SyntheticOptions o = test::smallOptions();
  o.scanLength_m = 0.1, o.lines = 50, o.photoWidth = 640, o.photoHeight = 480;
  o.targetViews = 3, o.clickNoise_px = 0.1;
  const SyntheticTruth truth = makeSyntheticTruth(o);
  const auto object = markedPoints(truth, 6, 0.1, 3);
  const auto views = syntheticTargetViews(truth);
  REQUIRE(views.size() == 3);
  for (const auto& view : views) CHECK(view.size() >= 60);  // most of the 11 x 11 grid inside the photo
  const CalibrationResult r = calibrateCamera(object, 640, 480, CalibrationPriors{}, "test", views);
  INFO("cx " << r.camera.cx << " +- " << r.std[2] << " cy " << r.camera.cy << " +- " << r.std[3] << " k1 " << r.camera.k1
             << " k2 " << r.camera.k2 << " +- " << r.std[5]);
  CHECK(r.views == 4);
  CHECK_FALSE(r.priors[2]);
  CHECK(std::abs(r.camera.cx - truth.camera.cx) < 3 * r.std[2] + 0.5);
  CHECK(std::abs(r.camera.cy - truth.camera.cy) < 3 * r.std[3] + 0.5);
  CHECK(r.reliable(0));
  CHECK(r.reliable(2));
  CHECK(r.reliable(3));
  CHECK(worldToPixelError(truth, r.camera) < 0.5);
}

TEST_CASE("a scan with several target views reports reliable intrinsics close to the truth, one view does not") {
  // End to end: the synthetic scanner writes calibration_view_N.csv and lists them in scan.json;
  // acquire -> writeDataset -> NAME_calibration.json.
  // A wide view (f ~ 560 px over a 640 x 480 photo: corners at r ~ 0.7), where k2 shows.
  SyntheticOptions o = test::smallOptions(SyntheticKind::PlasticGrid);
  o.photoWidth = 640, o.photoHeight = 480, o.photoScale_px_per_mm = 1.5;
  for (const int extra : {0, 4}) {
    o.targetViews = extra;
    const auto scan = test::writeScan("calibration_views_" + std::to_string(extra), o);
    const Scan loaded = loadScan(scan.dir);
    CHECK(loaded.calibrationViews.size() == std::size_t(extra));
    const auto out = vt::test::outputDir("calibration_views_out_" + std::to_string(extra));
    writeDataset(acquire(loaded, {.jobs = 2}), out);
    const std::string& object = scan.truth.options.name;
    const auto report = nlohmann::json::parse(std::ifstream(out / object / (object + "_calibration.json")));
    const auto& p = report["parameters"];
    const CameraModel& truth = scan.truth.camera;
    INFO(extra << " extra views: " << p.dump());
    CHECK(report["views"] == extra + 1);
    for (const char* name : {"cx", "cy", "k2"}) {
      CHECK(p[name]["reliable"] == (extra > 0));
      CHECK(p[name]["status"] == (extra > 0 ? "fitted" : "prior"));
    }
    if (extra == 0) continue;
    // Close to the truth: within three standard errors and within the reliability limits.
    const auto near = [&](const char* name, double value, double limit) {
      const double fitted = p[name]["value"].get<double>(), std = p[name]["std"].get<double>();
      INFO(name << " fitted " << fitted << " +- " << std << ", true " << value);
      CHECK(std::abs(fitted - value) < 3 * std + 1e-9);
      CHECK(std::abs(fitted - value) < limit);
    };
    near("cx", truth.cx, 2.0);
    near("cy", truth.cy, 2.0);
    near("k1", truth.k1, 0.01);
    near("k2", truth.k2, 0.01);
    near("fx", truth.fx, 0.005 * truth.fx);
  }
}

TEST_CASE("which settings make which intrinsics reliable, per camera (the table in docs/scan-format.md)") {
  // Cameras: the default photo (640 x 480, 2.9 px/mm at the object: a narrow view), the wide
  // test camera (640 x 480, 1.5 px/mm: corners at r ~ 0.7) and a 1920 x 1080 photo at the
  // default scale. Settings: one view; one view with a 1 % focal prior (true focal length, 1 %
  // std); four extra target views. A parameter counts as reliable when it is in all three seeds.
  struct Camera {
    const char* name;
    int width, height;
    double scale_px_per_mm;
  };
  const Camera cameras[] = {{"640x480 default", 640, 480, 2.9}, {"640x480 wide", 640, 480, 1.5}, {"1920x1080", 1920, 1080, 2.9}};
  const char* settings[] = {"one view", "one view + focal prior", "4 target views"};
  std::string table = "| camera | setting | fx | fy | cx | cy | k1 | k2 | std of fx | of cx | of k1 | of k2 |\n"
                      "|---|---|---|---|---|---|---|---|---|---|---|---|\n";
  // What docs/scan-format.md says ("Which settings make which parameters reliable"): reliable
  // fx fy cx cy k1 k2, per camera and setting.
  const char* documented[3][3] = {{"------", "------", "yyyyy-"}, {"------", "------", "yyyyyy"}, {"------", "------", "yyyyyy"}};
  for (const Camera& camera : cameras) {
    for (int setting = 0; setting < 3; ++setting) {
      std::array<bool, 6> reliable{true, true, true, true, true, true};
      std::array<double, 6> largestStd{};
      for (std::uint64_t seed = 1; seed <= 3; ++seed) {
        SyntheticOptions o = test::smallOptions();
        o.scanLength_m = 0.1, o.lines = 50, o.seed = seed;
        o.photoWidth = camera.width, o.photoHeight = camera.height, o.photoScale_px_per_mm = camera.scale_px_per_mm;
        o.targetViews = setting == 2 ? 4 : 0;
        const SyntheticTruth truth = makeSyntheticTruth(o);
        CalibrationPriors priors;
        if (setting == 1) priors.focal_px = std::array{truth.camera.fx, 0.01 * truth.camera.fx};
        const CalibrationResult r =
            calibrateCamera(markedPoints(truth, 5, 0.15, seed), camera.width, camera.height, priors, "t", syntheticTargetViews(truth));
        const CameraModel& c = r.camera;
        const CameraModel& t = truth.camera;
        const double fitted[6] = {c.fx, c.fy, c.cx, c.cy, c.k1, c.k2}, want[6] = {t.fx, t.fy, t.cx, t.cy, t.k1, t.k2};
        for (int i = 0; i < 6; ++i) {
          reliable[std::size_t(i)] = reliable[std::size_t(i)] && r.reliable(i);
          largestStd[std::size_t(i)] = std::max(largestStd[std::size_t(i)], r.std[std::size_t(i)] / (i < 2 ? want[i] : 1.0));
          // Reliable or not, the truth is within three reported standard errors.
          INFO(camera.name << ", " << settings[setting] << ", seed " << seed << ", parameter " << i << ": " << fitted[i]
                           << " +- " << r.std[std::size_t(i)] << ", true " << want[i]);
          CHECK(std::abs(fitted[i] - want[i]) <= 3 * r.std[std::size_t(i)]);
        }
      }
      std::string row = std::string("| ") + camera.name + " | " + settings[setting] + " |";
      std::string pattern;
      for (bool b : reliable) row += b ? " yes |" : " - |", pattern += b ? 'y' : '-';
      CHECK(pattern == documented[&camera - cameras][setting]);
      row += vt::str(" ", std::round(largestStd[0] * 1e4) / 1e2, " % | ", std::round(largestStd[2] * 10) / 10, " px | ",
                     std::round(largestStd[4] * 1e4) / 1e4, " | ", std::round(largestStd[5] * 1e4) / 1e4, " |");
      table += row + "\n";
    }
  }
  std::printf("%s", table.c_str());
}
