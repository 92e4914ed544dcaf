// Table I statistics against the synthetic scanner's ground truth, and the two methods
// (the paper's, the authors' code) on the same scan.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <string_view>

#include <nlohmann/json.hpp>

#include "scan_fixture.hpp"
#include "vt/acquisition/pipeline.hpp"
#include "vt/core/error.hpp"
#include "vt/scene/loaders.hpp"

using namespace vt::acq;

namespace {

// The ground truth of a taxel: the noise-free |a - 1 g| = |h''| v^2 / g at cruise speed
// (h'' along the pass) averaged over the taxel's extent. SyntheticTruth::vibration_g is the
// period average for a slowly varying roughness; this is exact also at sharp outlines.
double truthOfTaxel(const SyntheticTruth& truth, const LineResult& line, const Taxel& t) {
  constexpr int kSteps = 400;
  constexpr double kG = 9.80665, kH = 2e-6;
  const double v = truth.options.speed_m_s;
  double sum = 0;
  for (int k = 0; k < kSteps; ++k) {
    const double along = t.y0_m + (t.y1_m - t.y0_m) * (k + 0.5) / kSteps;
    const auto height = [&](double d) {
      const auto w = line.world(along + d);
      return truth.surface.surfaceHeight_m(w[0] - truth.objectX0_m, w[1] - truth.objectY0_m);
    };
    sum += std::abs((height(kH) - 2 * height(0) + height(-kH)) / (kH * kH)) * v * v / kG;
  }
  return sum / kSteps;
}

TaxelStats truthStats(const SyntheticTruth& truth, const std::vector<LineResult>& lines) {
  std::vector<double> values;
  for (const LineResult& line : lines)
    for (const Taxel& t : line.taxels) values.push_back(truthOfTaxel(truth, line, t));
  return computeStats(values);
}

}  // namespace

TEST_CASE("taxel statistics match the ground truth within 3 percent on every synthetic kind") {
  for (auto name : syntheticKindNames()) {
    SyntheticOptions o = test::smallOptions(parseSyntheticKind(name));
    // Accelerometer noise biases |a - g| upwards (E|s + n| > |s|), most on the smooth tile
    // whose signal is the size of the noise: the method is checked on the signal itself.
    o.accelNoise_g = 0.0;
    const auto scan = test::writeScan(std::string("truth_") + std::string(name), o);
    const AcquireResult r = acquire(loadScan(scan.dir), {.jobs = 2});
    const TaxelStats want = truthStats(scan.truth, r.lines);
    INFO(name << ": V_scale " << r.stats.scale << " vs " << want.scale << ", V_mean " << r.stats.mean << " vs "
              << want.mean << ", V_std " << r.stats.std << " vs " << want.std);
    CHECK(r.stats.scale == Approx(want.scale).epsilon(0.03));
    CHECK(r.stats.mean == Approx(want.mean).epsilon(0.03));
    CHECK(r.stats.std == Approx(want.std).epsilon(0.03));
    // Whole bins: every taxel within half a bin of the nominal size, none a sliver.
    for (const LineResult& line : r.lines) {
      for (const Taxel& t : line.taxels) {
        CHECK(std::abs(t.y1_m - t.y0_m - 0.001) < 0.0005);
      }
    }
  }
}

TEST_CASE("noise-corrected statistics against the ground truth at 0, 0.01 and 0.03 g of accelerometer noise") {
  // The raw statistics are inflated by noise (E|s + n| > |s|), most where the signal is the size
  // of the noise: the smooth tile (its scan is larger, 1000 taxels, for steadier V_std and
  // V_scale). The noise floor comes from the readings at rest. Tolerances: docs/scan-format.md,
  // "Sensor noise".
  for (auto name : {"smooth_ceramic_tile", "notebook_cover", "relief_ceramic_tile", "plastic_grid"}) {
    for (const double noise : {0.0, 0.01, 0.03}) {
      SyntheticOptions o = test::smallOptions(parseSyntheticKind(name));
      o.accelNoise_g = noise;
      const bool smooth = std::string_view(name) == "smooth_ceramic_tile";
      if (smooth) o.lines = 20, o.scanLength_m = 0.05;
      const auto scan = test::writeScan(vt::str("noise_", name, "_", noise), o);
      const AcquireResult r = acquire(loadScan(scan.dir), {.jobs = 2});
      const TaxelStats want = truthStats(scan.truth, r.lines);
      const TaxelStats& raw = r.stats;
      const TaxelStats& got = r.statsCorrected;
      INFO(name << " at " << noise << " g: noise floor " << r.noise.sigma_g << " from " << r.noise.samples
                << " readings; V_mean raw " << raw.mean << " corrected " << got.mean << " truth " << want.mean
                << "; V_std raw " << raw.std << " corrected " << got.std << " truth " << want.std << "; V_scale raw "
                << raw.scale << " corrected " << got.scale << " truth " << want.scale);
      REQUIRE(r.noise.known);
      CHECK(r.noise.sigma_g == Approx(noise).margin(1e-4).epsilon(0.03));
      CHECK(got.mean == Approx(want.mean).epsilon(noise < 0.02 ? 0.03 : 0.05));
      CHECK(got.std == Approx(want.std).epsilon(noise < 0.02 ? 0.05 : 0.2));
      CHECK(got.scale == Approx(want.scale).epsilon(noise == 0.0 ? 0.03 : noise < 0.02 ? 0.15 : 0.5));
      if (smooth && noise > 0) {
        CHECK(std::abs(got.mean - want.mean) < 0.2 * std::abs(raw.mean - want.mean));
        CHECK(std::abs(got.std - want.std) < 0.5 * std::abs(raw.std - want.std));
      }
    }
  }
}

TEST_CASE("the authors' code differs from the paper's method where documented") {
  const auto scan = test::writeScan("compat_reference", test::smallOptions(SyntheticKind::PlasticGrid));
  const Scan loaded = loadScan(scan.dir);
  const AcquireResult paper = acquire(loaded, {.jobs = 2});
  const AcquireResult reference = acquire(loaded, {.jobs = 2, .compat = Compat::Reference});
  CHECK(paper.config.compat == Compat::Paper);
  CHECK(reference.config.stretch_px == 4.0);
  REQUIRE(reference.lines.size() == paper.lines.size());
  for (std::size_t i = 0; i < paper.lines.size(); ++i) {
    const LineResult& p = paper.lines[i];
    const LineResult& c = reference.lines[i];
    for (std::size_t k = 0; k < p.passes.size(); ++k) {
      // +-2 robot samples at the window's ends (the first pass's travel sets the window),
      // no +-1 on the accelerometer side.
      CHECK(c.passes[k].i1 >= p.passes[k].i1);
      CHECK(c.passes[k].i2 <= p.passes[k].i2);
      CHECK(c.passes[k].i2 - c.passes[k].i1 + 4 == Approx(p.passes[k].i2 - p.passes[k].i1).margin(2));
    }
    // Fixed 1 mm bins inclusive at both ends, over 2 w l from the smallest position.
    for (const Taxel& t : c.taxels) CHECK(t.y1_m - t.y0_m == Approx(0.001));
    CHECK(c.taxels.size() <= std::size_t(std::ceil(2 * 0.45 * p.passes[0].travel_m / 0.001)) + 1);
    CHECK(c.taxels.back().y0_m < c.taxels.front().y0_m + 2 * 0.45 * p.passes[0].travel_m);
  }
}

TEST_CASE("reference binning counts boundary samples twice and stops at the first empty bin") {
  std::vector<PlacedSample> s{{0.0010, 1.0}, {0.0020, 3.0}, {0.0025, 5.0}, {0.0045, 7.0}};
  const auto taxels = binTaxelsReference(s, 0.5, 0.001, 0.004);
  REQUIRE(taxels.size() == 2);  // [1,2] [2,3]; [3,4] is empty, so [4,5] is never reached
  CHECK(taxels[0].v_g == Approx(2.0));  // 1 and the boundary sample 3
  CHECK(taxels[0].samples == 2);
  CHECK(taxels[1].v_g == Approx(4.0));  // the boundary sample again, and 5
}

TEST_CASE("paper binning makes whole bins over the measured span") {
  std::vector<PlacedSample> s;
  for (int i = 0; i <= 1010; ++i) s.push_back({0.01 + i * 1e-5, i < 1000 ? 1.0 : 9.0});  // 10.1 mm
  const auto taxels = binTaxels(s, 0.0, 0.001);
  REQUIRE(taxels.size() == 10);  // not 11 with a 0.1 mm sliver holding the last 10 samples
  CHECK(taxels.back().y1_m == Approx(0.0201));
  CHECK(taxels.back().y1_m - taxels.back().y0_m == Approx(0.00101));
  CHECK(taxels.back().v_g < 2.0);  // the odd samples are averaged with a whole bin
}

TEST_CASE("a scan in two directions gives two maps aligned to the same photo") {
  SyntheticOptions o = test::smallOptions(SyntheticKind::PlasticGrid);
  o.acrossPasses = true;
  o.accelNoise_g = 0.0;
  const auto scan = test::writeScan("two_directions", o);
  const AcquireResult r = acquire(loadScan(scan.dir), {.jobs = 2});
  REQUIRE(r.across);
  CHECK(r.axis == 1);
  CHECK(r.lines.size() == 6);
  CHECK(r.across->lines.size() == 10);  // 20 mm mapped length, one line per 2 mm
  for (const LineResult& line : r.across->lines) CHECK(line.axis == 0);
  // Each direction against its own ground truth (h'' along its passes).
  const TaxelStats wantAcross = truthStats(scan.truth, r.across->lines);
  CHECK(r.across->stats.mean == Approx(wantAcross.mean).epsilon(0.03));
  CHECK(r.across->stats.std == Approx(wantAcross.std).epsilon(0.03));
  // The fine texture runs along Y: felt crossing its ridges, barely along them.
  CHECK(r.across->stats.mean < 0.5 * r.stats.mean);
  // One pixel grid: both maps cover (nearly) the same pixels of the one photo.
  std::size_t both = 0, main = 0;
  for (std::size_t i = 0; i < r.map.coverage.pixels.size(); ++i) {
    main += r.map.coverage.pixels[i] != 0;
    both += r.map.coverage.pixels[i] != 0 && r.across->map.coverage.pixels[i] != 0;
  }
  CHECK(both > main * 8 / 10);
  // The top view puts +Y to the right (u) and +X down (-v).
  const glm::dvec2 alongUv = scanDirectionUv(r, 1), acrossUv = scanDirectionUv(r, 0);
  CHECK(alongUv.x == Approx(1.0).margin(0.02));
  CHECK(acrossUv.y == Approx(-1.0).margin(0.02));

  // The dataset carries both, and the scene gives the plate both maps and the direction.
  const auto out = vt::test::outputDir("two_directions_dataset");
  writeDataset(r, out);
  const vt::Scene scene = vt::loadDatasetScene(out);
  const auto it = std::find_if(scene.materials.begin(), scene.materials.end(),
                               [](const vt::Material& mat) { return mat.name == "plastic_grid"; });
  REQUIRE(it != scene.materials.end());
  const vt::Material& m = *it;
  REQUIRE(m.vibrationMapAcross >= 0);
  CHECK(m.scanDirectionUv.x == Approx(1.0f).margin(0.02f));
  const vt::ImageF& acrossMap = scene.vibrationMaps[std::size_t(m.vibrationMapAcross)];
  const vt::ImageF& mainMap = scene.vibrationMaps[std::size_t(m.vibrationMap)];
  CHECK(acrossMap.width == mainMap.width);

  // The across PNG spans its own range (all of it lies below the main map's minimum here: with
  // the main map's range it was all zeros), recorded in NAME_map.json.
  const auto meta = nlohmann::json::parse(std::ifstream(out / "plastic_grid" / "plastic_grid_map.json"));
  const double acrossLo = meta["across"]["normalisation"]["min_g"], acrossHi = meta["across"]["normalisation"]["max_g"];
  const double mainLo = meta["normalisation"]["min_g"], mainHi = meta["normalisation"]["max_g"];
  CHECK(acrossHi < mainLo);
  CHECK(acrossHi == Approx(r.across->stats.max).epsilon(0.02));
  const vt::Image16 acrossPng = vt::loadImage16(out / "plastic_grid" / "plastic_grid_acc_across.png", 1);
  CHECK(*std::max_element(acrossPng.pixels.begin(), acrossPng.pixels.end()) == 65535);
  // The loader brings both back to one scale, V / peak: the across map is felt at its own level
  // (a slide across the grid is not silent) and the main map keeps its values in g.
  const float acrossPeak = *std::max_element(acrossMap.pixels.begin(), acrossMap.pixels.end());
  const float mainPeak = *std::max_element(mainMap.pixels.begin(), mainMap.pixels.end());
  CHECK(mainPeak == Approx(1.0f).margin(1e-4));
  CHECK(acrossPeak == Approx(acrossHi / mainHi).epsilon(1e-3));
  std::size_t felt = 0, nonZero = 0;
  for (std::size_t i = 0; i < acrossPng.pixels.size(); ++i) {
    if (acrossPng.pixels[i] == 0) continue;
    ++nonZero;
    felt += acrossMap.pixels[i] > float(acrossLo / mainHi);
  }
  CHECK(felt == nonZero);
  CHECK(nonZero > acrossPng.pixels.size() / 10);  // noise-free, most of the across taxels are near 0 g
}
