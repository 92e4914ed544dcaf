// The pipeline against an independent, deliberately plain implementation of the same steps,
// the dataset writer's files, and the statistics table.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <sstream>

#include <nlohmann/json.hpp>

#include "scan_fixture.hpp"
#include "vt/acquisition/pipeline.hpp"
#include "vt/core/error.hpp"

using namespace vt::acq;
namespace fs = std::filesystem;

namespace {

struct Row {
  int pass;
  double t, a, b, c;
};

std::vector<Row> readCsv(const fs::path& path) {
  std::ifstream in(path);
  std::string line;
  std::getline(in, line);  // header
  std::vector<Row> rows;
  while (std::getline(in, line)) {
    std::replace(line.begin(), line.end(), ',', ' ');
    std::istringstream ss(line);
    Row r{};
    ss >> r.pass >> r.t >> r.a >> r.b >> r.c;
    rows.push_back(r);
  }
  return rows;
}

std::size_t argmin(const std::vector<double>& xs, double target) {
  std::size_t best = 0;
  for (std::size_t i = 0; i < xs.size(); ++i)
    if (std::abs(xs[i] - target) < std::abs(xs[best] - target)) best = i;
  return best;
}

// The paper's steps written out directly: (position, V) pooled over the passes of a line.
std::vector<std::pair<double, double>> plainLine(const fs::path& robotCsv, const fs::path& accelCsv, double offset) {
  const auto robot = readCsv(robotCsv), accel = readCsv(accelCsv);
  std::vector<std::pair<double, double>> pooled;
  for (int pass = 0; pass < 8; ++pass) {
    std::vector<double> t, y, ta, az;
    for (const Row& r : robot)
      if (r.pass == pass) t.push_back(r.t), y.push_back(r.b);
    for (const Row& r : accel)
      if (r.pass == pass) ta.push_back(r.t + offset), az.push_back(r.c);
    double mean = 0;
    for (double v : y) mean += v;
    mean /= double(y.size());
    const double l = *std::max_element(y.begin(), y.end()) - *std::min_element(y.begin(), y.end());
    std::size_t i1 = argmin(y, mean - 0.45 * l), i2 = argmin(y, mean + 0.45 * l);
    if (i1 > i2) std::swap(i1, i2);
    long double n = 0, st = 0, sy = 0, stt = 0, sty = 0;
    for (std::size_t i = i1; i <= i2; ++i) n += 1, st += t[i], sy += y[i], stt += t[i] * t[i], sty += t[i] * y[i];
    const double m = double((n * sty - st * sy) / (n * stt - st * st)), b = double((sy - (long double)m * st) / n);
    const std::size_t j1 = argmin(ta, t[i1]) + 1, j2 = argmin(ta, t[i2]) - 1;
    for (std::size_t j = j1; j <= j2; ++j) pooled.emplace_back(m * ta[j] + b, std::abs(az[j] - 1.0));
  }
  std::sort(pooled.begin(), pooled.end());
  return pooled;
}

}  // namespace

TEST_CASE("taxels and statistics equal an independent computation") {
  const auto scan = test::writeScan("stats_independent", test::smallOptions(SyntheticKind::GiftBox));
  const Scan loaded = loadScan(scan.dir);
  const AcquireResult r = acquire(loaded, {.jobs = 2});
  std::vector<long double> all;
  for (std::size_t line = 0; line < loaded.lines.size(); ++line) {
    const auto pooled = plainLine(loaded.lines[line].robot, loaded.lines[line].accel, loaded.config.accelClockOffset_s);
    // round(span / 1 mm) equal bins over the span (the last one closed), mean V per non-empty bin.
    const double y0 = pooled.front().first, span = pooled.back().first - y0;
    const double n = std::max(1.0, std::round(span / 0.001)), width = span / n;
    std::map<std::size_t, std::pair<double, int>> acc;
    for (const auto& [y, v] : pooled) {
      auto& cell = acc[std::min(std::size_t(n) - 1, std::size_t(std::floor((y - y0) / width)))];
      cell.first += v, cell.second += 1;
    }
    std::vector<std::pair<double, double>> bins;  // (start, mean)
    for (const auto& [bin, cell] : acc) bins.emplace_back(y0 + double(bin) * width, cell.first / cell.second);
    const auto& taxels = r.lines[line].taxels;
    REQUIRE(taxels.size() == bins.size());
    for (std::size_t i = 0; i < bins.size(); ++i) {
      CHECK(taxels[i].y0_m == Approx(bins[i].first).margin(1e-9));
      CHECK(taxels[i].v_g == Approx(bins[i].second).margin(1e-9));
      all.push_back(bins[i].second);
    }
  }
  long double sum = 0, sq = 0;
  for (long double v : all) sum += v, sq += v * v;
  const long double mean = sum / all.size();
  const double stdDev = double(std::sqrt(sq / all.size() - mean * mean));
  CHECK(r.stats.count == all.size());
  CHECK(r.stats.mean == Approx(double(mean)).epsilon(1e-9));
  CHECK(r.stats.std == Approx(stdDev).epsilon(1e-6));
  CHECK(r.stats.scale == Approx(double(*std::max_element(all.begin(), all.end()) - *std::min_element(all.begin(), all.end()))).epsilon(1e-9));
}

TEST_CASE("computeStats of known values") {
  const std::vector<double> v{1, 2, 3, 4};
  const TaxelStats s = computeStats(v);
  CHECK(s.scale == Approx(3));
  CHECK(s.mean == Approx(2.5));
  CHECK(s.std == Approx(std::sqrt(1.25)));
  CHECK(computeStats({}).count == 0);
}

TEST_CASE("dataset writer output and the stats table agree") {
  const auto scan = test::writeScan("stats_writer", test::smallOptions(SyntheticKind::PlasticGrid));
  const AcquireResult r = acquire(loadScan(scan.dir));
  const fs::path out = vt::test::outputDir("stats_writer_dataset");
  writeDataset(r, out);
  const fs::path obj = out / "plastic_grid";
  for (const char* suffix : {".png", "_acc.png", "_map.json", "_map.f32", "_preview.png", "_calibration.json"}) {
    CHECK(fs::is_regular_file(obj / (std::string("plastic_grid") + suffix)));
  }
  const auto acc = vt::loadImage16(obj / "plastic_grid_acc.png", 1);
  const auto photo = vt::loadImage8(obj / "plastic_grid.png", 3);
  CHECK(acc.width == photo.width);
  CHECK(acc.height == photo.height);
  CHECK(*std::max_element(acc.pixels.begin(), acc.pixels.end()) == 65535);
  const auto header = nlohmann::json::parse(std::ifstream(obj / "plastic_grid_map.json"));
  CHECK(header["width"] == acc.width);
  CHECK(fs::file_size(obj / "plastic_grid_map.f32") == std::size_t(acc.width) * acc.height * 4);
  CHECK(header["mm_per_pixel"][0].get<double>() == Approx(0.25).epsilon(0.02));  // 4 px/mm top view
  CHECK(header["physical_size_m"][0].get<double>() == Approx(0.02));

  const auto rows = datasetStats(out);
  REQUIRE(rows.size() == 1);
  CHECK(rows[0].source == StatsSource::Taxels);
  CHECK(rows[0].stats.mean == Approx(r.stats.mean));
  CHECK(rows[0].stats.scale == Approx(r.stats.scale));
  CHECK_THAT(statsTable(rows), Catch::Contains("plastic_grid") && Catch::Contains("taxels (g)"));
  CHECK_THAT(statsCsv(rows), Catch::StartsWith("name,source,v_scale,v_mean,v_std,count,noise_g,v_scale_corrected,v_mean_corrected,"
                                                "v_std_corrected\nplastic_grid,taxels_g,"));
  // The noise floor and the corrected statistics travel from NAME_map.json to the table.
  REQUIRE(r.noise.known);
  REQUIRE(rows[0].noise_g);
  CHECK(*rows[0].noise_g == Approx(r.noise.sigma_g));
  REQUIRE(rows[0].corrected);
  CHECK(rows[0].corrected->mean == Approx(r.statsCorrected.mean));
  const auto json = nlohmann::json::parse(statsJson(rows));
  CHECK(json[0]["noise_corrected"]["v_std"].get<double>() == Approx(r.statsCorrected.std));
  CHECK_THROWS_WITH(datasetStats(out / "plastic_grid"), Catch::Contains("no object folders"));
}

TEST_CASE("stats on the published dataset use the normalised maps") {
  const auto dir = vt::test::datasetDir();
  if (!dir) VT_SKIP("published dataset not present");
  const auto rows = datasetStats(*dir);
  REQUIRE(rows.size() == 8);
  CHECK(rows.front().name == "gift_box");
  for (const auto& row : rows) {
    INFO(row.name);
    CHECK(row.source == StatsSource::NormalisedPng);
    CHECK(row.stats.count > 10000);
    CHECK(row.stats.mean > 0.0);
    CHECK(row.stats.mean < 1.0);
    CHECK(row.stats.scale <= 1.0);
  }
  CHECK_THAT(statsTable(rows), Catch::Contains("normalised map*") && Catch::Contains("relief_ceramic_tile"));
}
