// Log and calibration CSV parsing: hand-rolled over std::from_chars because a 100 mm scan
// has about a million accelerometer rows and must load in a fraction of a second.
#include <charconv>
#include <cmath>
#include <cstdint>
#include <fstream>

#include "log_rows.hpp"
#include "mapped_file.hpp"
#include "vt/acquisition/scan.hpp"
#include "vt/core/budgets.hpp"
#include "vt/core/error.hpp"
#include "vt/core/file_io.hpp"

namespace vt::acq {
namespace {

bool isBlank(std::string_view line) {
  for (char c : line) {
    if (c != ' ' && c != '\t' && c != '\r') return false;
  }
  return true;
}

// A header line starts with a letter (numbers start with a digit, sign or dot).
bool isHeader(std::string_view line) {
  for (char c : line) {
    if (c == ' ' || c == '\t') continue;
    return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || c == '_';
  }
  return false;
}

std::string_view trim(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t' || s.back() == '\r')) s.remove_suffix(1);
  return s;
}

constexpr double kPow10[] = {1e0,  1e1,  1e2,  1e3,  1e4,  1e5,  1e6,  1e7,  1e8,  1e9,  1e10, 1e11,
                             1e12, 1e13, 1e14, 1e15, 1e16, 1e17, 1e18, 1e19, 1e20, 1e21, 1e22};

// Fast path for plain decimals like "-12.345678", the logs' usual form: when the digits fit
// in 2^53 and the scale is an exact power of ten, one division is correctly rounded, so the
// result equals from_chars'. Anything else (exponents, long mantissas, nan) returns false.
bool parsePlainDecimal(const char* p, const char* end, double& out) noexcept {
  const bool negative = p < end && *p == '-';
  if (negative) ++p;
  std::uint64_t mantissa = 0;
  int digits = 0, fraction = 0;
  bool dot = false, digitBeforeDot = false, digitAfterDot = false;
  for (; p < end; ++p) {
    const char c = *p;
    if (c >= '0' && c <= '9') {
      if (++digits > 19) return false;
      mantissa = mantissa * 10 + std::uint64_t(c - '0');
      (dot ? digitAfterDot : digitBeforeDot) = true;
      if (dot) ++fraction;
    } else if (c == '.' && !dot) {
      dot = true;
    } else {
      return false;
    }
  }
  if (!digitBeforeDot || (dot && !digitAfterDot) || mantissa > (std::uint64_t(1) << 53) || fraction > 22) return false;
  const double value = double(mantissa) / kPow10[fraction];
  out = negative ? -value : value;
  return true;
}

// Splits one line into exactly `count` numeric fields; `names` label them in errors.
template <std::size_t N>
void parseFields(std::string_view line, const std::string& source, std::size_t lineNo,
                 const std::array<std::string_view, N>& names, std::array<double, N>& out) {
  std::size_t field = 0;
  while (true) {
    const std::size_t comma = line.find(',');
    const std::string_view text = trim(line.substr(0, comma));
    if (field >= N) fail(source, ":", lineNo, ": expected ", N, " columns, found more");
    if (text.empty()) fail(source, ":", lineNo, ": column '", names[field], "' is empty");
    const char* begin = text.data();
    const char* const end = text.data() + text.size();
    if (*begin == '+') ++begin;
    if (!parsePlainDecimal(begin, end, out[field])) {
      const auto [stop, ec] = std::from_chars(begin, end, out[field]);
      if (ec != std::errc() || stop != end) {
        fail(source, ":", lineNo, ": column '", names[field], "' is not a number: '", text, "'");
      }
    }
    if (!std::isfinite(out[field])) fail(source, ":", lineNo, ": column '", names[field], "' is NaN or infinite");
    ++field;
    if (comma == std::string_view::npos) break;
    line.remove_prefix(comma + 1);
  }
  if (field != N) fail(source, ":", lineNo, ": expected ", N, " columns, found ", field);
}

// Calls `row(lineNo, line)` for every non-blank, non-header line.
template <class Row>
void forEachRow(std::string_view text, Row&& row) {
  std::size_t lineNo = 0;
  bool first = true;
  while (!text.empty()) {
    const std::size_t nl = text.find('\n');
    const std::string_view line = text.substr(0, nl);
    text.remove_prefix(nl == std::string_view::npos ? text.size() : nl + 1);
    ++lineNo;
    if (isBlank(line)) continue;
    if (first && isHeader(line)) {
      first = false;
      continue;
    }
    first = false;
    row(lineNo, line);
  }
}

}  // namespace

std::vector<PassSeries> parseLogCsv(std::string_view text, const std::string& source, const LogColumns& columns) {
  const std::array<std::string_view, 5> names{"pass", "t_s", columns[0], columns[1], columns[2]};
  PassCollector passes;
  std::array<double, 5> f{};
  forEachRow(text, [&](std::size_t lineNo, std::string_view line) {
    parseFields(line, source, lineNo, names, f);
    passes.add(f, [&] { return str(source, ":", lineNo); });
  });
  return passes.finish(source);
}

std::vector<Correspondence> parseCalibrationCsv(std::string_view text, const std::string& source) {
  static constexpr std::array<std::string_view, 4> names{"x_m", "y_m", "u_px", "v_px"};
  std::vector<Correspondence> points;
  std::array<double, 4> f{};
  forEachRow(text, [&](std::size_t lineNo, std::string_view line) {
    parseFields(line, source, lineNo, names, f);
    points.push_back({f[0], f[1], f[2], f[3]});
  });
  return points;
}

std::string readTextFile(const std::filesystem::path& path, std::string_view what) {
  // Names folders, symlink loops and permission problems, and holds the scan-line budget.
  return readInputFile(path, what, budget::kScanLogBytes);
}

namespace {

// A log file by its name: .npy arrays or CSV text, either read straight from a mapping.
std::vector<PassSeries> readLog(const std::filesystem::path& path, std::string_view what, const std::string& name,
                                const LogColumns& columns) {
  const MappedFile file(path, what);
  return path.extension() == ".npy" ? parseLogNpy(file.bytes(), name, columns)
                                    : parseLogCsv(file.bytes(), name, columns);
}

}  // namespace

LineLogs loadLine(const LineFiles& files, const ScanConfig& config) {
  LineLogs logs;
  const std::string robotName = files.robot.string();
  const std::string accelName = files.accel.string();
  logs.robot = readLog(files.robot, "robot log", robotName, kRobotColumns);
  logs.accel = readLog(files.accel, "accelerometer log", accelName, kAccelColumns);
  const auto expected = std::size_t(config.passesPerLine);
  if (logs.robot.size() != expected) {
    fail(robotName, ": has ", logs.robot.size(), " passes, scan.json passes_per_line says ", expected);
  }
  if (logs.accel.size() != expected) {
    fail(accelName, ": has ", logs.accel.size(), " passes, scan.json passes_per_line says ", expected);
  }
  return logs;
}

}  // namespace vt::acq
