#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <string>

#include "scan_fixture.hpp"
#include "vt/acquisition/alignment.hpp"
#include "vt/core/error.hpp"

using namespace vt::acq;

TEST_CASE("constant-velocity window excludes the ramps and positions match the stylus") {
  const auto scan = test::writeScan("alignment_window", test::smallOptions(SyntheticKind::PlasticGrid));
  const Scan loaded = loadScan(scan.dir);
  const SyntheticTruth& truth = scan.truth;
  const double offset = truth.options.accelClockOffset_s;
  for (int line : {0, 5}) {
    const LineLogs logs = loadLine(loaded.lines[std::size_t(line)], loaded.config);
    for (int pass = 0; pass < truth.options.passes; ++pass) {
      const auto& robot = logs.robot[std::size_t(pass)];
      const auto& accel = logs.accel[std::size_t(pass)];
      std::vector<PlacedSample> placed;
      const PassFit fit = fitPass(robot, accel, loaded.config, "test", std::size_t(pass), placed);
      const auto cruise = truth.cruise_s(line, pass);
      INFO("line " << line << " pass " << pass);
      CHECK(robot.t_s[fit.i1] >= cruise[0]);
      CHECK(robot.t_s[fit.i2] <= cruise[1]);
      CHECK(accel.t_s[fit.j1] + offset >= cruise[0]);
      CHECK(accel.t_s[fit.j2] + offset <= cruise[1]);
      CHECK(std::abs(std::abs(fit.slope_m_per_s) - truth.options.speed_m_s) < 1e-4);
      CHECK((fit.slope_m_per_s > 0) == (pass % 2 == 0));
      REQUIRE(placed.size() == fit.j2 - fit.j1 + 1);
      double worst = 0;
      for (std::size_t j = fit.j1; j <= fit.j2; ++j) {
        const double trueY = truth.stylusY_m(line, pass, accel.t_s[j] + offset);
        worst = std::max(worst, std::abs(placed[j - fit.j1].y_m - trueY));
      }
      CHECK(worst < 0.5e-3);
      CHECK(worst < 0.05e-3);  // in practice the fit is far better than the requirement
      // Each sample's taxel, from its recovered position, is the one its true position falls in
      // (or a neighbour when it lies within the position error of a bin edge).
      std::vector<PlacedSample> pooled = placed;
      const auto taxels = binTaxels(pooled, 0.0, 0.001);
      const double y0 = taxels.front().y0_m;
      for (std::size_t j = fit.j1; j <= fit.j2; ++j) {
        const double trueY = truth.stylusY_m(line, pass, accel.t_s[j] + offset);
        const double assigned = std::floor((placed[j - fit.j1].y_m - y0) / 0.001), actual = std::floor((trueY - y0) / 0.001);
        if (assigned != actual) CHECK(std::abs(trueY - (y0 + 0.001 * std::max(assigned, actual))) < 0.05e-3);
      }
    }
  }
}

TEST_CASE("taxel bins sit where their samples were taken") {
  const auto scan = test::writeScan("alignment_taxels", test::smallOptions());
  const Scan loaded = loadScan(scan.dir);
  const SyntheticTruth& truth = scan.truth;
  const LineResult line = processLine(loadLine(loaded.lines[2], loaded.config), loaded.config, "test");
  CHECK(std::abs(line.x_m - truth.lineX_m[2]) < 0.1e-3);
  REQUIRE(line.taxels.size() >= 20);
  for (const Taxel& t : line.taxels) {
    CHECK(t.y1_m - t.y0_m == Approx(0.001).epsilon(0.03));  // whole bins over the span: within half a bin in 20
    CHECK(t.samples > 50);
    // The bin centre lies within the scanned window and the mapped span.
    const double centre = 0.5 * (t.y0_m + t.y1_m);
    CHECK(centre > truth.windowY0_m - 0.5e-3);
    CHECK(centre < truth.windowY1_m + 0.5e-3);
  }
  // The bins cover the window from its start: the first bin starts within 0.5 mm of it.
  CHECK(std::abs(line.taxels.front().y0_m - truth.windowY0_m) < 0.5e-3);
  CHECK(std::abs(line.taxels.back().y1_m - truth.windowY1_m) < 1.0e-3);
}

TEST_CASE("lines processed in reused buffers equal lines processed alone, for odd and even pass counts") {
  for (int passes : {5, 8}) {
    SyntheticOptions o = test::smallOptions();
    o.passes = passes;
    const auto scan = test::writeScan("alignment_buffers_" + std::to_string(passes), o);
    const Scan loaded = loadScan(scan.dir);
    LineBuffers buffers;  // one worker's buffers across every line
    for (std::size_t i = 0; i < loaded.lines.size(); ++i) {
      const LineLogs logs = loadLine(loaded.lines[i], loaded.config);
      const LineResult alone = processLine(logs, loaded.config, "test");
      const LineResult reused = processLine(logs, loaded.config, "test", 1, buffers, false);
      // The merged passes are every placed sample, sorted by position.
      std::size_t placed = 0;
      for (const PassFit& fit : alone.passes) placed += fit.j2 - fit.j1 + 1;
      CHECK(buffers.pooled.size() == placed);
      CHECK(std::is_sorted(buffers.pooled.begin(), buffers.pooled.end(),
                           [](const PlacedSample& a, const PlacedSample& b) { return a.y_m < b.y_m; }));
      // The first pass is kept (for waveforms) only when asked, in time order.
      CHECK(alone.firstPass.size() == alone.passes[0].j2 - alone.passes[0].j1 + 1);
      CHECK(std::is_sorted(alone.firstPass.begin(), alone.firstPass.end(),
                           [](const PlacedSample& a, const PlacedSample& b) { return a.t_s < b.t_s; }));
      CHECK(reused.firstPass.empty());
      REQUIRE(reused.taxels.size() == alone.taxels.size());
      for (std::size_t k = 0; k < alone.taxels.size(); ++k) {
        CHECK(reused.taxels[k].y0_m == alone.taxels[k].y0_m);
        CHECK(reused.taxels[k].y1_m == alone.taxels[k].y1_m);
        CHECK(reused.taxels[k].v_g == alone.taxels[k].v_g);
        CHECK(reused.taxels[k].samples == alone.taxels[k].samples);
      }
      CHECK(reused.x_m == alone.x_m);
    }
  }
}

TEST_CASE("binning averages per bin from the smallest position and skips empty bins") {
  std::vector<PlacedSample> s{{0.0042, 3.0}, {0.0010, 1.0}, {0.0014, 2.0}, {0.0031, 5.0}, {0.0036, 6.0}, {0.0050, 3.0}};
  const auto taxels = binTaxels(s, 0.5, 0.001);
  REQUIRE(taxels.size() == 3);  // [1,2) [3,4) [4,5] mm; [2,3) is empty
  CHECK(taxels[0].y0_m == Approx(0.0010));
  CHECK(taxels[0].v_g == Approx(1.5));
  CHECK(taxels[1].y0_m == Approx(0.0030));
  CHECK(taxels[1].v_g == Approx(5.5));
  CHECK(taxels[2].y1_m == Approx(0.0050));
  CHECK(taxels[2].v_g == Approx(3.0));
  CHECK(taxels[2].samples == 2);  // the last bin is closed: the largest position belongs to it
  CHECK(taxels[0].x_m == 0.5);
}

TEST_CASE("a pass without a constant-velocity phase is rejected") {
  ScanConfig config;
  PassSeries robot, accel;
  // Triangular speed profile: accelerate to the middle, then decelerate; never constant.
  for (int i = 0; i <= 200; ++i) {
    const double t = i * 0.01, s = t < 1 ? 0.05 * t * t : 0.1 - 0.05 * (2 - t) * (2 - t);
    robot.t_s.push_back(t);
    robot.v.push_back({0.3, s, 0.0});
  }
  for (int j = 0; j <= 1000; ++j) {
    accel.t_s.push_back(j * 0.002);
    accel.v.push_back({0, 0, 1});
  }
  std::vector<PlacedSample> out;
  CHECK_THROWS_WITH(fitPass(robot, accel, config, "line_007_robot.csv", 3, out),
                    Catch::Contains("line_007_robot.csv") && Catch::Contains("pass 3 has no constant-velocity phase"));
  // A robot standing still has no phase either.
  for (auto& v : robot.v) v[1] = 0.02;
  CHECK_THROWS_WITH(fitPass(robot, accel, config, "r.csv", 0, out), Catch::Contains("no constant-velocity phase"));
}
