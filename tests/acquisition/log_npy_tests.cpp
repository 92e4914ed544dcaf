#include <catch2/catch.hpp>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>

#include "vt/acquisition/scan.hpp"
#include "vt/core/error.hpp"

using namespace vt::acq;

namespace {

const char* const kCsv = "pass,t_s,x_m,y_m,z_m\n0,0.0,1,2,3\n0,0.1,1,2.5,3\n1,0.2,-1,2,3.25\n";

// A .npy file with the given header dict and raw data (version 1.0 framing).
std::string npy(const std::string& dict, const std::string& data) {
  std::string header = dict + "\n";
  std::string out = "\x93NUMPY";
  out += '\x01';
  out += '\x00';
  out += char(header.size() & 0xff);
  out += char(header.size() >> 8);
  return out + header + data;
}

template <class T>
std::string values(std::initializer_list<T> v) {
  std::string out(v.size() * sizeof(T), '\0');
  std::memcpy(out.data(), std::data(v), out.size());
  return out;
}

std::string npyErrorOf(const std::string& bytes) {
  try {
    parseLogNpy(bytes, "robot.npy", kRobotColumns);
  } catch (const vt::Error& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST_CASE("log npy round trip equals the csv it came from") {
  const auto fromCsv = parseLogCsv(kCsv, "r.csv", kRobotColumns);
  const std::string bytes = formatLogNpy(fromCsv);
  CHECK(bytes.find("'descr': '<f8'") != std::string::npos);
  const auto fromNpy = parseLogNpy(bytes, "r.npy", kRobotColumns);
  REQUIRE(fromNpy.size() == fromCsv.size());
  for (std::size_t p = 0; p < fromCsv.size(); ++p) {
    CHECK(fromNpy[p].t_s == fromCsv[p].t_s);
    CHECK(fromNpy[p].v == fromCsv[p].v);
  }
}

TEST_CASE("log npy reads float32 and column-major arrays") {
  const auto f4 = parseLogNpy(npy("{'descr': '<f4', 'fortran_order': False, 'shape': (2, 5), }",
                                  values<float>({0, 0.5f, 1, 2, 3, 0, 0.75f, 4, 5, 6})),
                              "a.npy", kAccelColumns);
  REQUIRE(f4.size() == 1);
  CHECK(f4[0].t_s == std::vector<double>{0.5, 0.75});
  CHECK(f4[0].v[1][2] == 6.0);
  // Column-major: the pass column first, then t_s, ...
  const auto fortran = parseLogNpy(npy("{'descr': '<f8', 'fortran_order': True, 'shape': (2, 5), }",
                                       values<double>({0, 1, 0.1, 0.2, 7, 8, 9, 10, 11, 12})),
                                   "a.npy", kAccelColumns);
  REQUIRE(fortran.size() == 2);
  CHECK(fortran[1].t_s[0] == 0.2);
  CHECK(fortran[1].v[0] == std::array<double, 3>{8, 10, 12});
}

TEST_CASE("log npy rejects bad files naming the file and the field") {
  const std::string row = values<double>({0, 0.0, 1, 2, 3});
  CHECK_THAT(npyErrorOf("pass,t_s\n"), Catch::Contains("robot.npy") && Catch::Contains("not a .npy file"));
  CHECK_THAT(npyErrorOf(npy("{'descr': '>f8', 'fortran_order': False, 'shape': (1, 5), }", row)),
             Catch::Contains("dtype '>f8'"));
  CHECK_THAT(npyErrorOf(npy("{'descr': '<i4', 'fortran_order': False, 'shape': (1, 5), }", row)),
             Catch::Contains("dtype '<i4'"));
  CHECK_THAT(npyErrorOf(npy("{'descr': '<f8', 'fortran_order': False, 'shape': (1, 4), }", row)),
             Catch::Contains("shape (1, 4)"));
  CHECK_THAT(npyErrorOf(npy("{'descr': '<f8', 'fortran_order': False, 'shape': (5,), }", row)),
             Catch::Contains("expected (rows, 5)"));
  CHECK_THAT(npyErrorOf(npy("{'descr': '<f8', 'fortran_order': False, 'shape': (2, 5), }", row)),
             Catch::Contains("data is 40 bytes"));
  CHECK_THAT(npyErrorOf(npy("{'descr': '<f8', 'fortran_order': False, 'shape': (99999999999999999, 5), }", row)),
             Catch::Contains("data is 40 bytes"));
  CHECK_THAT(npyErrorOf(npy("{'descr': '<f8', 'shape': (1, 5), }", row)), Catch::Contains("no 'fortran_order'"));
  CHECK_THAT(npyErrorOf(npy("{'descr': '<f8', 'fortran_order': False, 'shape': (0, 5), }", "")),
             Catch::Contains("no samples"));
  CHECK_THAT(npyErrorOf(npy("{'descr': '<f8', 'fortran_order': False, 'shape': (1, 5), }",
                         values<double>({0, 0.0, 1, std::nan(""), 3}))),
             Catch::Contains("row 0") && Catch::Contains("'y_m' is NaN or infinite"));
  CHECK_THAT(npyErrorOf(npy("{'descr': '<f8', 'fortran_order': False, 'shape': (2, 5), }",
                         values<double>({0, 0.2, 1, 2, 3, 0, 0.1, 1, 2, 3}))),
             Catch::Contains("robot.npy: row 1") && Catch::Contains("non-monotonic"));
  std::string cut = npy("{'descr': '<f8', 'fortran_order': False, 'shape': (1, 5), }", row);
  cut[8] = char(0xff);  // header length past the end
  CHECK_THAT(npyErrorOf(cut), Catch::Contains("header runs past the end"));
}

TEST_CASE("a scan whose logs are npy files loads like its csv original") {
  const std::filesystem::path dir = std::filesystem::path(VT_TEST_OUTPUT_DIR) / "log_npy_scan";
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  const auto passes = parseLogCsv(kCsv, "r.csv", kRobotColumns);
  std::ofstream(dir / "robot.csv") << kCsv;
  std::ofstream(dir / "robot.npy", std::ios::binary) << formatLogNpy(passes);
  ScanConfig config;
  config.passesPerLine = 2;
  const LineLogs csv = loadLine({dir / "robot.csv", dir / "robot.csv"}, config);
  const LineLogs bin = loadLine({dir / "robot.npy", dir / "robot.npy"}, config);
  CHECK(bin.robot[1].t_s == csv.robot[1].t_s);
  CHECK(bin.accel[0].v == csv.accel[0].v);
  CHECK_THROWS_WITH(loadLine({dir / "missing.npy", dir / "robot.npy"}, config),
                    Catch::Contains("robot log") && Catch::Contains("missing.npy': file not found"));
}

TEST_CASE("log npy reads arrays numpy itself wrote") {
  // np.save of the same three rows as float64, float32 and Fortran order (fuzz seed corpus).
  const std::filesystem::path dir = std::filesystem::path(VT_SOURCE_DIR) / "tests/fuzz/corpus/fuzz_scan_npy";
  for (const char* name : {"accel_f8.npy", "accel_f4.npy", "accel_fortran.npy"}) {
    INFO(name);
    std::ifstream in(dir / name, std::ios::binary);
    const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    const auto passes = parseLogNpy(bytes, name, kAccelColumns);
    REQUIRE(passes.size() == 2);
    REQUIRE(passes[0].t_s.size() == 2);
    CHECK(passes[0].t_s[1] == Approx(0.001));
    CHECK(passes[1].v[0][2] == Approx(0.97));
  }
  std::ifstream in(dir / "truncated.npy", std::ios::binary);
  const std::string cut((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  CHECK_THROWS_WITH(parseLogNpy(cut, "truncated.npy", kAccelColumns), Catch::Contains("truncated.npy: .npy data is"));
}
