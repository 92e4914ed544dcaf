// A small committed scan (tests/acquisition/data/golden_scan) through the whole pipeline,
// compared with committed outputs. On a mismatch the actual files and a diff image are left
// in the test output folder; VT_UPDATE_GOLDEN=1 rewrites the goldens after a deliberate change.
#include <catch2/catch.hpp>

#include <cstdlib>
#include <fstream>

#include <nlohmann/json.hpp>

#include "test_support.hpp"
#include "vt/acquisition/pipeline.hpp"

using namespace vt::acq;
namespace fs = std::filesystem;

TEST_CASE("golden scan reproduces its committed outputs") {
  const fs::path data = vt::test::sourceDir() / "tests/acquisition/data";
  const fs::path out = vt::test::outputDir("golden");
  const AcquireResult r = acquire(loadScan(data / "golden_scan"), {.jobs = 2});
  writeDataset(r, out, false);
  const fs::path actual = out / "golden_tile", expected = data / "golden_expected";
  const char* files[] = {"golden_tile.png", "golden_tile_acc.png", "golden_tile_map.json"};
  if (std::getenv("VT_UPDATE_GOLDEN")) {
    fs::create_directories(expected);
    for (const char* f : files) fs::copy_file(actual / f, expected / f, fs::copy_options::overwrite_existing);
    WARN("golden files rewritten in " << expected.string());
    return;
  }
  const auto want = nlohmann::json::parse(std::ifstream(expected / "golden_tile_map.json"));
  const auto got = nlohmann::json::parse(std::ifstream(actual / "golden_tile_map.json"));
  for (const char* key : {"v_scale_g", "v_mean_g", "v_std_g", "v_min_g", "v_max_g"}) {
    INFO(key);
    CHECK(got["statistics"][key].get<double>() == Approx(want["statistics"][key].get<double>()).epsilon(1e-7));
  }
  CHECK(got["statistics"]["taxels"] == want["statistics"]["taxels"]);
  CHECK(got["width"] == want["width"]);
  CHECK(got["height"] == want["height"]);

  const auto a = vt::loadImage16(actual / "golden_tile_acc.png", 1), e = vt::loadImage16(expected / "golden_tile_acc.png", 1);
  REQUIRE(a.width == e.width);
  REQUIRE(a.height == e.height);
  vt::Image8 diff(a.width, a.height, 1);
  int worst = 0;
  for (std::size_t i = 0; i < a.pixels.size(); ++i) {
    const int d = std::abs(int(a.pixels[i]) - int(e.pixels[i]));
    worst = std::max(worst, d);
    diff.pixels[i] = std::uint8_t(std::min(255, d / 16));
  }
  vt::savePng(out / "golden_tile_acc_diff.png", diff);
  INFO("actual and diff images in " << out.string());
  CHECK(worst <= 64);  // 0.1% of full scale: room for floating-point differences between builds
  const auto pa = vt::loadImage8(actual / "golden_tile.png", 3), pe = vt::loadImage8(expected / "golden_tile.png", 3);
  REQUIRE(pa.pixels.size() == pe.pixels.size());
  int photoWorst = 0;
  for (std::size_t i = 0; i < pa.pixels.size(); ++i) photoWorst = std::max(photoWorst, std::abs(int(pa.pixels[i]) - int(pe.pixels[i])));
  CHECK(photoWorst <= 1);
}
