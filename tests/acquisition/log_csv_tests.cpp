#include <catch2/catch.hpp>

#include <array>
#include <charconv>
#include <random>
#include <string>
#include <vector>

#include "vt/acquisition/scan.hpp"
#include "vt/core/error.hpp"

using namespace vt::acq;

namespace {
std::string csvErrorOf(const std::string& text) {
  try {
    parseLogCsv(text, "robot.csv", kRobotColumns);
  } catch (const vt::Error& e) {
    return e.what();
  }
  return "";
}
}  // namespace

TEST_CASE("log csv parses passes with and without header") {
  const auto passes = parseLogCsv("pass,t_s,x_m,y_m,z_m\n0,0.0,1,2,3\n0,0.1,1,2.5,3\n1,0.2,1,2,3\n", "r.csv", kRobotColumns);
  REQUIRE(passes.size() == 2);
  CHECK(passes[0].t_s.size() == 2);
  CHECK(passes[0].v[1][1] == Approx(2.5));
  CHECK(passes[1].t_s[0] == Approx(0.2));
  const auto noHeader = parseLogCsv("0,1e-3,+1,-2,3\r\n\n0,2e-3,1,2,3", "r.csv", kRobotColumns);
  REQUIRE(noHeader.size() == 1);
  CHECK(noHeader[0].v[0][1] == Approx(-2));
}

TEST_CASE("log csv rejects malformed rows naming file line and column") {
  CHECK_THAT(csvErrorOf("0,0.0,1,2\n"), Catch::Contains("robot.csv:1") && Catch::Contains("expected 5 columns"));
  CHECK_THAT(csvErrorOf("0,0.0,1,2,3,4\n"), Catch::Contains("found more"));
  CHECK_THAT(csvErrorOf("0,0.0,abc,2,3\n"), Catch::Contains("column 'x_m' is not a number"));
  CHECK_THAT(csvErrorOf("0,0.0,nan,2,3\n"), Catch::Contains("'x_m' is NaN or infinite"));
  CHECK_THAT(csvErrorOf("0,inf,1,2,3\n"), Catch::Contains("'t_s' is NaN or infinite"));
  CHECK_THAT(csvErrorOf("0,0.0,1,,3\n"), Catch::Contains("column 'y_m' is empty"));
  CHECK_THAT(csvErrorOf("0.5,0.0,1,2,3\n"), Catch::Contains("non-negative integer"));
  CHECK_THAT(csvErrorOf("1,0.0,1,2,3\n"), Catch::Contains("out of order"));
  CHECK_THAT(csvErrorOf("0,0.1,1,2,3\n0,0.1,1,2,3\n"), Catch::Contains("robot.csv:2") && Catch::Contains("non-monotonic"));
  CHECK_THAT(csvErrorOf("0,0.1,1,2,3\n0,0.2,1,2,3\n1,0.15,1,2,3\n"), Catch::Contains("overlapping timestamps"));
  CHECK_THAT(csvErrorOf("0,0.1,1,2,3\n1,0.2,1,2,3\n0,0.3,1,2,3\n"), Catch::Contains("out of order"));
  CHECK_THAT(csvErrorOf("pass,t_s,x_m,y_m,z_m\n"), Catch::Contains("no samples"));
}

TEST_CASE("calibration csv parses four columns") {
  const auto pts = parseCalibrationCsv("x_m,y_m,u_px,v_px\n0.1,0.2,10,20\n", "c.csv");
  REQUIRE(pts.size() == 1);
  CHECK(pts[0].v_px == Approx(20));
  CHECK_THROWS_WITH(parseCalibrationCsv("0.1,0.2,10\n", "c.csv"), Catch::Contains("c.csv:1"));
}

TEST_CASE("log csv numbers equal from_chars for every digit count and row position") {
  // Plain decimals of 1..20 digits with the dot anywhere, in every value column, at the end of
  // the text too: rows with 120 bytes after them take the short-row parser (no bounds checks,
  // up to 7 + 7 digits), longer numbers and the last rows the bounded one-pass parser (it reads
  // 8 bytes at a time and must stop at the text's end).
  std::mt19937_64 rng(18);
  std::vector<std::string> numbers;
  for (int digits = 1; digits <= 20; ++digits) {
    for (int dot = 0; dot <= digits; ++dot) {
      std::string n = rng() % 2 ? "-" : "";
      for (int d = 0; d < digits; ++d) {
        if (d == dot && dot > 0) n += '.';
        n += char('0' + rng() % 10);
      }
      numbers.push_back(n);
    }
  }
  std::string text = "pass,t_s,x_m,y_m,z_m\n";
  std::vector<double> expected;
  for (std::size_t i = 0; i + 2 < numbers.size(); i += 3) {
    const std::string t = std::to_string(i + 1);
    text += "0," + t + "," + numbers[i] + "," + numbers[i + 1] + "," + numbers[i + 2] + (i % 2 ? "\r\n" : "\n");
    for (std::size_t k = i; k < i + 3; ++k) {
      double v = 0;
      const char* begin = numbers[k].data();
      std::from_chars(begin, begin + numbers[k].size(), v);
      expected.push_back(v);
    }
  }
  text.pop_back();  // the last row without its newline
  if (text.back() == '\r') text.pop_back();
  const auto passes = parseLogCsv(text, "r.csv", kRobotColumns);
  REQUIRE(passes.size() == 1);
  REQUIRE(passes[0].v.size() * 3 == expected.size());
  for (std::size_t r = 0; r < passes[0].v.size(); ++r) {
    for (std::size_t c = 0; c < 3; ++c) {
      INFO("row " << r << " column " << c << ": " << numbers[3 * r + c]);
      CHECK(passes[0].v[r][c] == expected[3 * r + c]);  // bit-exact, not approximate
    }
  }
  // The same numbers four to a row of a calibration file: every column, the first included.
  std::string calibration = "x_m,y_m,u_px,v_px\n";
  for (std::size_t i = 0; i + 3 < numbers.size(); i += 4) {
    calibration += numbers[i] + "," + numbers[i + 1] + "," + numbers[i + 2] + "," + numbers[i + 3] + "\n";
  }
  const auto points = parseCalibrationCsv(calibration, "c.csv");
  REQUIRE(points.size() == numbers.size() / 4);
  for (std::size_t r = 0; r < points.size(); ++r) {
    const std::array<double, 4> got{points[r].x_m, points[r].y_m, points[r].u_px, points[r].v_px};
    for (std::size_t c = 0; c < 4; ++c) {
      const std::string& n = numbers[4 * r + c];
      double want = 0;
      std::from_chars(n.data(), n.data() + n.size(), want);
      INFO("calibration row " << r << " column " << c << ": " << n);
      CHECK(got[c] == want);
    }
  }
}
