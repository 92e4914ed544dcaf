// `--compat reference` draws the map as the authors' run.py does: against a PNG their own
// pipeline wrote for a small synthetic scan (tests/acquisition/data/authors_reference/README.md).
#include <catch2/catch.hpp>

#include <fstream>

#include <nlohmann/json.hpp>

#include "scan_fixture.hpp"
#include "vt/acquisition/authors_map.hpp"
#include "vt/acquisition/pipeline.hpp"

using namespace vt::acq;
namespace fs = std::filesystem;

namespace {

// The scan of the README's `vtouching acquire --synthetic plastic_grid --authors-rig ...`.
test::ScanOnDisk authorsRigScan(const std::string& name) {
  SyntheticOptions o;
  o.kind = SyntheticKind::PlasticGrid;
  o.authorsRig = true;
  o.scanLength_m = 0.04, o.lines = 6;
  o.photoWidth = 320, o.photoHeight = 240, o.topViewScale_px_per_mm = 4.0;
  return test::writeScan(name, o);
}

// The share of pixels of `ours` equal to the stored map of the authors' pipeline.
double shareEqual(const vt::Image8& ours, const vt::Image8& theirs) {
  REQUIRE(ours.width == theirs.width);
  REQUIRE(ours.height == theirs.height);
  std::size_t equal = 0;
  for (std::size_t i = 0; i < ours.pixels.size(); ++i) equal += ours.pixels[i] == theirs.pixels[i];
  return double(equal) / double(ours.pixels.size());
}

}  // namespace

TEST_CASE("the reference mode with the authors' camera draws their map pixel for pixel") {
  const fs::path data = vt::test::sourceDir() / "tests/acquisition/data/authors_reference";
  const auto scan = authorsRigScan("authors_map");
  // The camera their code calibrates, recorded in scan.json as the importer's --authors-camera does.
  nlohmann::json doc = nlohmann::json::parse(std::ifstream(scan.dir / "scan.json"));
  doc["camera"] = nlohmann::json::parse(std::ifstream(data / "camera.json"));
  std::ofstream(scan.dir / "scan.json") << doc.dump(2);
  const AcquireResult r = acquire(loadScan(scan.dir), {.jobs = 2, .compat = Compat::Reference});
  REQUIRE(r.authorsMap);
  REQUIRE(r.calibration.given);
  const vt::Image8 theirs = vt::loadImage8(data / "plastic_grid_acc.png", 1);
  const double equal = shareEqual(*r.authorsMap, theirs);
  INFO(100 * equal << " % of the pixels equal");
  CHECK(equal >= 0.999);
  std::size_t covered = 0;
  for (std::uint8_t p : theirs.pixels) covered += p > 0;
  CHECK(covered > theirs.pixels.size() / 2);  // a map, not an empty image that matches trivially

  // The dataset carries it as NAME_acc.png (8 bits); the paper's mode keeps the project's drawing.
  const auto out = vt::test::outputDir("authors_map_dataset");
  writeDataset(r, out, false, true);
  CHECK(shareEqual(vt::loadImage8(out / "plastic_grid" / "plastic_grid_acc.png", 1), theirs) >= 0.999);
  const auto meta = nlohmann::json::parse(std::ifstream(out / "plastic_grid" / "plastic_grid_map.json"));
  CHECK(meta["map_png_bits"] == 8);
  CHECK_FALSE(acquire(loadScan(scan.dir), {.jobs = 2, .compat = Compat::Paper}).authorsMap);
}

TEST_CASE("the authors' drawing follows numpy's slices and OpenCV's warp steps") {
  // One line of two taxels seen by a camera whose image u runs against Y: the rectangles span
  // rows y - 4 .. y + 3 and the columns from the end point to the start point.
  LineResult line;
  line.axis = 1;
  line.firstPassX_m = 0.0;
  line.taxels = {{0.0, 0.000, 0.010, 1.0, 1}, {0.0, 0.010, 0.020, 2.0, 1}};
  CameraModel camera;
  camera.fx = camera.fy = 1000, camera.cx = 50, camera.cy = 20;
  camera.rvec = {0, 0, 1.5707963267948966};  // 90 degrees about the optical axis: u = cx - 1000 Y, v = cy + 1000 X
  camera.t_m = {0, 0, 1};
  const vt::ImageF map = drawTaxelsAsAuthors(std::span(&line, 1), camera, 80, 40);
  // Y 0 .. 0.01 -> u 50 .. 40: columns 40 .. 49; the second taxel columns 30 .. 39; row y = 20.
  CHECK(map.at(45, 16) == 1.0f);
  CHECK(map.at(45, 23) == 1.0f);
  CHECK(map.at(45, 24) == 0.0f);
  CHECK(map.at(45, 15) == 0.0f);
  CHECK(map.at(50, 20) == 0.0f);
  CHECK(map.at(40, 20) == 1.0f);
  CHECK(map.at(39, 20) == 2.0f);
  // A half-pixel shift lands on 16/32 exactly: the two taps weigh one half each.
  const vt::ImageF shifted = warpAsOpenCv(map, {1, 0, -0.5, 0, 1, 0, 0, 0, 1}, 80, 40);
  CHECK(shifted.at(39, 20) == Approx(1.5f));
}
