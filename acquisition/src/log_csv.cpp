// Log and calibration CSV parsing: hand-rolled over std::from_chars because a 100 mm scan
// has about a million accelerometer rows and must load in a fraction of a second.
#include <bit>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>
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

constexpr std::uint64_t kPow10Int[] = {1, 10, 100, 1000, 10000, 100000, 1000000, 10000000, 100000000};

// The number spelled by the n (1..8) digits at p, from one 8-byte load (SWAR: no per-digit
// work).
[[gnu::always_inline]] inline std::uint64_t digitsValue(const char* p, int n) noexcept {
  std::uint64_t chunk;
  std::memcpy(&chunk, p, 8);  // byte k = character k (little-endian)
  // Digit values, the n digits moved to the top bytes (the bytes below are leading zeros);
  // borrows from bytes after the digits leave with the shift.
  std::uint64_t d = (chunk - 0x3030303030303030u) << (8 * (8 - n));
  // Each multiply-add joins neighbours: a byte with 10 x the one before it (the more
  // significant digit), then 16 bits with 100 x those before, then 32 bits with 10000 x.
  d = ((d * (10 * 256 + 1)) >> 8) & 0x00FF00FF00FF00FFu;      // pairs of digits in 16 bits
  d = ((d * (100 * 65536 + 1)) >> 16) & 0x0000FFFF0000FFFFu;  // groups of four in 32 bits
  return (d * ((std::uint64_t(10000) << 32) + 1)) >> 32;      // all eight
}

// The decimal digits at the start of the 8 bytes at p (SWAR: no per-byte branches): returns
// how many there are (0..8) and sets `value` to the number they spell.
[[gnu::always_inline]] inline int leadingDigits8(const char* p, std::uint64_t& value) noexcept {
  std::uint64_t chunk;
  std::memcpy(&chunk, p, 8);  // byte k = character k (little-endian)
  // A byte is a digit when it stays below 0x80 both minus '0' and plus 0x46 ('9' + 0x46 =
  // 0x7F). A borrow or carry out of a non-digit byte can spoil only the bytes after it, which
  // are not counted.
  const std::uint64_t notDigit =
      ((chunk - 0x3030303030303030u) | (chunk + 0x4646464646464646u)) & 0x8080808080808080u;
  const int n = notDigit ? std::countr_zero(notDigit) / 8 : 8;
  if (n > 0) value = digitsValue(p, n);
  return n;
}

// Appends the run of digits at p to `mantissa`, counting them in `count`; returns its end.
// Past 19 digits the mantissa may wrap, which the caller rejects by the count.
const char* digitRun(const char* p, const char* end, std::uint64_t& mantissa, std::ptrdiff_t& count) noexcept {
  while (end - p >= 8) {
    std::uint64_t value = 0;
    const int n = leadingDigits8(p, value);
    mantissa = mantissa * kPow10Int[n] + value;
    count += n, p += n;
    if (n < 8) return p;
  }
  for (; p < end && unsigned(*p - '0') < 10u; ++p, ++count) mantissa = mantissa * 10 + std::uint64_t(*p - '0');
  return p;
}

// A number in the logs' usual form, [-]W or [-]W.F with 1..7 digits W and F, at p, with 17
// bytes readable there (no bounds checks); returns the byte after it, or nullptr for any other
// form. Each digit is checked by its own branch: a log's columns keep their widths, so these
// are predicted and where the next field starts does not wait for the digits' loads (counting
// the fraction's digits from its 8-byte load instead made the fields one dependent chain and
// the parse slower). W.F is (W x 10^|F| + F) / 10^|F|, at most 14 digits, exact in a double,
// so the one division rounds correctly and the value equals from_chars'.
[[gnu::always_inline]] inline const char* parseShortDecimal(const char* p, double& out) noexcept {
  const bool negative = *p == '-';
  if (negative) ++p;
  std::uint64_t whole = 0;
  int wholeDigits = 0;
  for (; wholeDigits < 8 && unsigned(p[wholeDigits] - '0') < 10u; ++wholeDigits) {
    whole = whole * 10 + std::uint64_t(p[wholeDigits] - '0');
  }
  if (wholeDigits == 0 || wholeDigits == 8) return nullptr;
  p += wholeDigits;
  double value = double(std::int64_t(whole));
  if (*p == '.') {
    int fractionDigits = 0;
    while (fractionDigits < 8 && unsigned(p[1 + fractionDigits] - '0') < 10u) ++fractionDigits;
    if (fractionDigits == 0 || fractionDigits == 8) return nullptr;
    const std::uint64_t fraction = digitsValue(p + 1, fractionDigits);
    value = double(std::int64_t(whole * kPow10Int[fractionDigits] + fraction)) / kPow10[fractionDigits];
    p += 1 + fractionDigits;
  }
  out = negative ? -value : value;
  return p;
}

// One plain decimal like "-12.345678" at p, up to the first byte that is not part of it;
// returns that byte's address, or nullptr when the text is not in this form or not exactly
// representable this way. When the digits fit in 2^53 and the scale is an exact power of ten,
// one division is correctly rounded, so the value equals from_chars'.
[[gnu::always_inline]] inline const char* parsePlainDecimal(const char* p, const char* end, double& out) noexcept {
  if (end - p >= 17) {
    if (const char* next = parseShortDecimal(p, out)) return next;
  }
  const bool negative = p < end && *p == '-';
  if (negative) ++p;
  std::uint64_t mantissa = 0;
  std::ptrdiff_t intDigits = 0, fraction = 0;
  p = digitRun(p, end, mantissa, intDigits);
  if (p < end && *p == '.') {
    p = digitRun(p + 1, end, mantissa, fraction);
    if (fraction == 0) return nullptr;
  }
  // 19 digits cannot overflow 64 bits; 2^53 keeps the mantissa exact in a double.
  if (intDigits == 0 || intDigits + fraction > 19 || mantissa > (std::uint64_t(1) << 53) || fraction > 22) {
    return nullptr;
  }
  const double value = double(mantissa) / kPow10[fraction];
  out = negative ? -value : value;
  return p;
}

// A row of N numbers in parseShortDecimal's form separated by single commas and ending at
// '\n' ("\r\n"), with 24 x N bytes readable at p, so no byte needs a bounds check; returns
// the start of the next row, or nullptr for any other form (left to parsePlainRow).
template <std::size_t N>
[[gnu::always_inline]] inline const char* parseShortRow(const char* p, std::array<double, N>& out) noexcept {
#pragma GCC unroll 8
  for (std::size_t k = 0; k < N; ++k) {
    p = parseShortDecimal(p, out[k]);
    if (!p) return nullptr;
    if (k + 1 < N) {
      if (*p++ != ',') return nullptr;
    } else {
      if (*p == '\r') ++p;
      if (*p++ != '\n') return nullptr;
    }
  }
  return p;
}

// A whole row of N plain decimals separated by single commas, ending at '\n' ("\r\n") or the
// end of the text, parsed in one pass; returns the start of the next row, or nullptr for any
// other form (spaces, exponents, a header, a blank or short line), which the caller then
// reads field by field with full checks and error messages.
template <std::size_t N>
[[gnu::always_inline]] inline const char* parsePlainRow(const char* p, const char* end, std::array<double, N>& out) noexcept {
  for (std::size_t k = 0; k < N; ++k) {
    p = parsePlainDecimal(p, end, out[k]);
    if (!p) return nullptr;
    if (k + 1 < N) {
      if (p == end || *p != ',') return nullptr;
      ++p;
    }
  }
  if (p < end && *p == '\r') ++p;
  if (p == end) return p;
  return *p == '\n' ? p + 1 : nullptr;
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
    if (parsePlainDecimal(begin, end, out[field]) != end) {
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

// Calls `row(lineNo, fields)` for every non-blank, non-header line of N numbers; `names` label
// the columns in errors. Rows in the plain form take the one-pass path, others the checked one.
template <std::size_t N, class Row>
void forEachRow(std::string_view text, const std::string& source, const std::array<std::string_view, N>& names,
                Row&& row) {
  std::array<double, N> f{};
  std::size_t lineNo = 0;
  bool first = true;
  const char* p = text.data();
  const char* const end = p + text.size();
  while (p < end) {
    ++lineNo;
    const char* next = end - p >= std::ptrdiff_t(24 * N) ? parseShortRow(p, f) : nullptr;
    if (!next) next = parsePlainRow(p, end, f);
    if (next) {
      p = next;
      first = false;
      row(lineNo, f);
      continue;
    }
    const auto* nl = static_cast<const char*>(std::memchr(p, '\n', std::size_t(end - p)));
    const std::string_view line(p, std::size_t((nl ? nl : end) - p));
    p = nl ? nl + 1 : end;
    if (isBlank(line)) continue;
    if (first && isHeader(line)) {
      first = false;
      continue;
    }
    first = false;
    parseFields(line, source, lineNo, names, f);
    row(lineNo, f);
  }
}

}  // namespace

std::vector<PassSeries> parseLogCsv(std::string_view text, const std::string& source, const LogColumns& columns) {
  const std::array<std::string_view, 5> names{"pass", "t_s", columns[0], columns[1], columns[2]};
  PassCollector passes;
  forEachRow(text, source, names, [&](std::size_t lineNo, const std::array<double, 5>& f) {
    passes.add(f, [&] { return str(source, ":", lineNo); });
  });
  return passes.finish(source);
}

std::vector<Correspondence> parseCalibrationCsv(std::string_view text, const std::string& source) {
  static constexpr std::array<std::string_view, 4> names{"x_m", "y_m", "u_px", "v_px"};
  std::vector<Correspondence> points;
  forEachRow(text, source, names,
             [&](std::size_t, const std::array<double, 4>& f) { points.push_back({f[0], f[1], f[2], f[3]}); });
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
