// Every malformed-input case of the scan format gives a clear error naming file and problem.
#include <catch2/catch.hpp>

#include <fstream>
#include <sstream>

#include "scan_fixture.hpp"
#include "vt/acquisition/pipeline.hpp"
#include "vt/core/error.hpp"

using namespace vt::acq;
namespace fs = std::filesystem;

namespace {

// A small scan of its own for each case: ctest runs every case as its own process, in
// parallel, so a shared pristine copy would be rewritten by one case while another copies it.
fs::path copyScan(const std::string& name) {
  SyntheticOptions o = test::smallOptions();
  o.lines = 3;
  return test::writeScan("errors_" + name, o).dir;
}

std::vector<std::string> readLines(const fs::path& path) {
  std::ifstream in(path);
  std::vector<std::string> lines;
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

void writeLines(const fs::path& path, const std::vector<std::string>& lines) {
  std::ofstream out(path);
  for (const auto& line : lines) out << line << '\n';
}

std::vector<std::string> split(const std::string& row) {
  std::vector<std::string> out;
  std::stringstream ss(row);
  for (std::string f; std::getline(ss, f, ',');) out.push_back(f);
  return out;
}

std::string join(const std::vector<std::string>& f) {
  std::string s;
  for (std::size_t i = 0; i < f.size(); ++i) s += (i ? "," : "") + f[i];
  return s;
}

// Runs load + acquire and returns the error message ("" when it succeeded).
std::string acquireError(const fs::path& dir) {
  try {
    acquire(loadScan(dir), {.jobs = 2});
  } catch (const vt::Error& e) {
    return e.what();
  }
  return "";
}

void replaceInFile(const fs::path& path, const std::string& from, const std::string& to) {
  std::ifstream in(path);
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const auto at = text.find(from);
  REQUIRE(at != std::string::npos);
  text.replace(at, from.size(), to);
  std::ofstream(path) << text;
}

}  // namespace

TEST_CASE("the pristine scan processes without error") { CHECK(acquireError(copyScan("none")).empty()); }

TEST_CASE("missing files are named") {
  auto dir = copyScan("missing_json");
  fs::remove(dir / "scan.json");
  CHECK_THAT(acquireError(dir), Catch::Contains("scan.json") && Catch::Contains("file not found"));
  dir = copyScan("missing_photo");
  fs::remove(dir / "photo.png");
  CHECK_THAT(acquireError(dir), Catch::Contains("photo") && Catch::Contains("photo.png") && Catch::Contains("file not found"));
  dir = copyScan("missing_calibration");
  fs::remove(dir / "calibration.csv");
  CHECK_THAT(acquireError(dir), Catch::Contains("calibration.csv") && Catch::Contains("file not found"));
  dir = copyScan("missing_log");
  fs::remove(dir / "lines/line_001_accel.csv");
  CHECK_THAT(acquireError(dir), Catch::Contains("lines[1]") && Catch::Contains("line_001_accel.csv") &&
                                    Catch::Contains("file not found"));
  CHECK_THAT(acquireError(vt::test::outputDir("errors_empty_dir") / "nothing"), Catch::Contains("not found"));
}

TEST_CASE("too few calibration points") {
  const auto dir = copyScan("few_points");
  auto rows = readLines(dir / "calibration.csv");
  rows.resize(1 + 5);  // header + 5 points
  writeLines(dir / "calibration.csv", rows);
  CHECK_THAT(acquireError(dir), Catch::Contains("calibration.csv") && Catch::Contains("too few calibration points: 5"));
}

TEST_CASE("nan and inf in logs") {
  auto dir = copyScan("nan");
  auto rows = readLines(dir / "lines/line_002_accel.csv");
  auto f = split(rows[40]);
  f[4] = "nan";
  rows[40] = join(f);
  writeLines(dir / "lines/line_002_accel.csv", rows);
  CHECK_THAT(acquireError(dir), Catch::Contains("line_002_accel.csv:41") && Catch::Contains("'az_g' is NaN or infinite"));
  dir = copyScan("inf");
  rows = readLines(dir / "lines/line_000_robot.csv");
  f = split(rows[10]);
  f[3] = "-inf";
  rows[10] = join(f);
  writeLines(dir / "lines/line_000_robot.csv", rows);
  CHECK_THAT(acquireError(dir), Catch::Contains("line_000_robot.csv:11") && Catch::Contains("'y_m' is NaN or infinite"));
}

TEST_CASE("non-monotonic and overlapping timestamps") {
  auto dir = copyScan("non_monotonic");
  auto rows = readLines(dir / "lines/line_001_robot.csv");
  std::swap(rows[20], rows[21]);
  writeLines(dir / "lines/line_001_robot.csv", rows);
  CHECK_THAT(acquireError(dir), Catch::Contains("line_001_robot.csv:22") && Catch::Contains("non-monotonic timestamps in pass 0"));

  dir = copyScan("overlapping");
  rows = readLines(dir / "lines/line_001_accel.csv");
  // The first row of pass 1 gets a time inside pass 0.
  std::size_t first = 0;
  for (std::size_t i = 1; i < rows.size(); ++i) {
    if (rows[i].rfind("1,", 0) == 0) {
      first = i;
      break;
    }
  }
  REQUIRE(first > 2);
  auto f = split(rows[first]);
  f[1] = split(rows[first - 2])[1];
  rows[first] = join(f);
  writeLines(dir / "lines/line_001_accel.csv", rows);
  CHECK_THAT(acquireError(dir), Catch::Contains("line_001_accel.csv") && Catch::Contains("overlapping timestamps") &&
                                    Catch::Contains("pass 1 starts"));
}

TEST_CASE("a pass without constant velocity") {
  const auto dir = copyScan("no_cv");
  auto rows = readLines(dir / "lines/line_002_robot.csv");
  // Pass 3 loses its constant phase: a 2 mm bump in the middle of its travel.
  std::vector<std::size_t> pass3;
  for (std::size_t i = 1; i < rows.size(); ++i)
    if (rows[i].rfind("3,", 0) == 0) pass3.push_back(i);
  REQUIRE(pass3.size() > 50);
  for (std::size_t k = pass3.size() / 3; k < 2 * pass3.size() / 3; ++k) {
    auto f = split(rows[pass3[k]]);
    f[3] = std::to_string(std::stod(f[3]) + 0.002);
    rows[pass3[k]] = join(f);
  }
  writeLines(dir / "lines/line_002_robot.csv", rows);
  CHECK_THAT(acquireError(dir), Catch::Contains("line_002_robot.csv") && Catch::Contains("pass 3 has no constant-velocity phase"));
}

TEST_CASE("mismatched clocks") {
  const auto dir = copyScan("clocks");
  replaceInFile(dir / "scan.json", "\"accel_clock_offset_s\": 12.5", "\"accel_clock_offset_s\": 0.0");
  CHECK_THAT(acquireError(dir), Catch::Contains("mismatched clocks") && Catch::Contains("accel_clock_offset_s"));
}

namespace {

// The error acquire gives for a copy of the scan whose scan.json has `from` replaced by `to`.
std::string scanJsonError(const std::string& name, const std::string& from, const std::string& to) {
  const auto dir = copyScan(name);
  replaceInFile(dir / "scan.json", from, to);
  return acquireError(dir);
}

// The same with `fields` (JSON members) added to scan.json.
std::string scanJsonErrorWith(const std::string& name, const std::string& fields) {
  return scanJsonError(name, "\"passes_per_line\": 8", fields + ", \"passes_per_line\": 8");
}

}  // namespace

TEST_CASE("scan json problems") {
  using Catch::Contains;
  CHECK_THAT(scanJsonError("passes", "\"passes_per_line\": 8", "\"passes_per_line\": 7"),
             Contains("has 8 passes") && Contains("passes_per_line says 7"));
  CHECK_THAT(scanJsonError("unknown_field", "\"passes_per_line\"", "\"passes_per_lin\""),
             Contains("unknown field 'passes_per_lin'"));
  CHECK_THAT(scanJsonError("window", "\"window_w\": 0.45", "\"window_w\": 0.9"), Contains("'window_w' = 0.9 out of range"));
  CHECK_THAT(scanJsonError("crop", "\"crop\": [\n    8,", "\"crop\": [\n    800,"), Contains("field 'crop'") && Contains("exceeds"));
  CHECK_THAT(scanJsonError("json", "{", "["), Contains("scan.json") && Contains("invalid JSON"));
}

TEST_CASE("a bad focal prior or given camera in scan.json is named") {
  using Catch::Contains;
  CHECK_THAT(scanJsonErrorWith("focal", "\"focal_px\": [1000, 0]"),
             Contains("scan.json") && Contains("'focal_px' must be F or [F, STD]"));
  CHECK_THAT(scanJsonErrorWith("camera_missing", "\"camera\": {\"fx\": 1000}"), Contains("field 'camera.fy' is missing"));
  CHECK_THAT(scanJsonErrorWith("camera_behind", "\"camera\": {\"fx\": 1000, \"fy\": 1000, \"cx\": 160, \"cy\": 120, "
                                                "\"distortion\": [0, 0, 0, 0, 0], \"rvec\": [0, 0, 0], \"t_m\": [0, 0, -1]}"),
             Contains("'camera.t_m' must put the object in front of the camera"));
  CHECK_THAT(scanJsonErrorWith("camera_key", "\"camera\": {\"f\": 1000}"), Contains("unknown field 'camera.f'"));
}
