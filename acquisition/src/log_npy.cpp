// Scan logs as NumPy .npy arrays (the form the authors published their logs in): an N x 5
// float64 or float32 array, rows (pass, t_s, c0, c1, c2). Binary: no number parsing.
#include <bit>
#include <charconv>
#include <cstdint>
#include <cstring>

#include "log_rows.hpp"
#include "vt/acquisition/scan.hpp"
#include "vt/core/error.hpp"

namespace vt::acq {
namespace {

static_assert(std::endian::native == std::endian::little, ".npy logs are read as little-endian");

constexpr std::string_view kMagic = "\x93NUMPY";

std::uint32_t littleEndian(std::string_view bytes, std::size_t at, std::size_t count) {
  std::uint32_t v = 0;
  for (std::size_t i = 0; i < count; ++i) v |= std::uint32_t(std::uint8_t(bytes[at + i])) << (8 * i);
  return v;
}

// The text after `'key':` in the header dict (a Python literal), up to the value's end:
// a quoted string without its quotes, a tuple with its parentheses, or a bare word.
std::string_view dictValue(std::string_view header, std::string_view key, const std::string& source) {
  std::size_t at = std::string_view::npos;
  for (const char quote : {'\'', '"'}) {
    const std::string quoted = str(quote, key, quote);
    at = header.find(quoted);
    if (at != std::string_view::npos) {
      at += quoted.size();
      break;
    }
  }
  if (at == std::string_view::npos) fail(source, ": .npy header has no '", key, "'");
  while (at < header.size() && (header[at] == ' ' || header[at] == ':')) ++at;
  if (at >= header.size()) fail(source, ": .npy header: '", key, "' has no value");
  const char c = header[at];
  std::size_t end;
  if (c == '\'' || c == '"') {
    end = header.find(c, at + 1);
    if (end == std::string_view::npos) fail(source, ": .npy header: '", key, "' is an unterminated string");
    return header.substr(at + 1, end - at - 1);
  }
  end = header.find(c == '(' ? ')' : ',', at);
  if (end == std::string_view::npos) fail(source, ": .npy header: '", key, "' has no end");
  return header.substr(at, end - at + (c == '(' ? 1 : 0));
}

// "(N, 5)" -> N; anything else is an error naming the shape.
std::uint64_t rowCount(std::string_view shape, const std::string& source) {
  std::uint64_t dims[3] = {};
  int count = 0;
  std::string_view rest = shape.substr(1, shape.size() - 2);  // inside the parentheses
  while (!rest.empty()) {
    while (!rest.empty() && (rest.front() == ' ' || rest.front() == ',')) rest.remove_prefix(1);
    if (rest.empty()) break;
    if (count == 3) break;
    const auto [stop, ec] = std::from_chars(rest.data(), rest.data() + rest.size(), dims[count]);
    if (ec != std::errc()) fail(source, ": .npy shape ", shape, " is not a tuple of sizes");
    rest.remove_prefix(std::size_t(stop - rest.data()));
    ++count;
  }
  if (count != 2 || dims[1] != 5) {
    fail(source, ": .npy shape ", shape, ": expected (rows, 5) for pass, t_s and three values");
  }
  return dims[0];
}

}  // namespace

std::vector<PassSeries> parseLogNpy(std::string_view bytes, const std::string& source, const LogColumns& columns) {
  if (bytes.size() < 10 || bytes.substr(0, kMagic.size()) != kMagic) {
    fail(source, ": not a .npy file (no \\x93NUMPY magic)");
  }
  const unsigned major = std::uint8_t(bytes[6]);
  std::size_t headerLength = 0, offset = 0;
  if (major == 1) {
    headerLength = littleEndian(bytes, 8, 2);
    offset = 10;
  } else if (major == 2 || major == 3) {
    if (bytes.size() < 12) fail(source, ": .npy header is cut short");
    headerLength = littleEndian(bytes, 8, 4);
    offset = 12;
  } else {
    fail(source, ": .npy format version ", major, " is not supported (1, 2 or 3)");
  }
  if (headerLength > bytes.size() - offset) fail(source, ": .npy header runs past the end of the file");
  const std::string_view header = bytes.substr(offset, headerLength);
  const std::string_view data = bytes.substr(offset + headerLength);

  const std::string_view descr = dictValue(header, "descr", source);
  std::size_t itemSize = 0;
  if (descr == "<f8") itemSize = 8;
  else if (descr == "<f4") itemSize = 4;
  else fail(source, ": .npy dtype '", descr, "' is not supported (little-endian float64 '<f8' or float32 '<f4')");
  const std::string_view order = dictValue(header, "fortran_order", source);
  if (order != "False" && order != "True") fail(source, ": .npy fortran_order '", order, "' is not True or False");
  const bool columnMajor = order == "True";
  const std::string_view shape = dictValue(header, "shape", source);
  if (shape.size() < 2 || shape.front() != '(') fail(source, ": .npy shape '", shape, "' is not a tuple");
  const std::uint64_t rows = rowCount(shape, source);
  if (rows > data.size() / (5 * itemSize) || rows * 5 * itemSize != data.size()) {
    fail(source, ": .npy data is ", data.size(), " bytes, shape ", shape, " of ", descr, " needs ",
         rows <= data.size() ? rows * 5 * itemSize : rows, rows <= data.size() ? " bytes" : " rows");
  }

  const std::array<std::string_view, 5> names{"pass", "t_s", columns[0], columns[1], columns[2]};
  PassCollector passes;
  // One loop per layout, so the element reads are not branches per value.
  const auto readRows = [&](auto value) {
    std::array<double, 5> f{};
    for (std::uint64_t row = 0; row < rows; ++row) {
      for (std::size_t c = 0; c < 5; ++c) {
        f[c] = value(row, c);
        if (!std::isfinite(f[c])) fail(source, ": row ", row, ": column '", names[c], "' is NaN or infinite");
      }
      passes.add(f, [&] { return str(source, ": row ", row); });
    }
  };
  const auto element = [&](auto item, std::uint64_t index) {
    decltype(item) v;
    std::memcpy(&v, data.data() + index * sizeof v, sizeof v);
    return double(v);
  };
  const auto readAs = [&](auto item) {
    if (columnMajor) {
      readRows([&](std::uint64_t row, std::size_t column) { return element(item, column * rows + row); });
    } else {
      readRows([&](std::uint64_t row, std::size_t column) { return element(item, row * 5 + column); });
    }
  };
  if (itemSize == 8) readAs(double{});
  else readAs(float{});
  return passes.finish(source);
}

std::string formatLogNpy(const std::vector<PassSeries>& passes) {
  std::size_t rows = 0;
  for (const PassSeries& p : passes) rows += p.t_s.size();
  std::string header = str("{'descr': '<f8', 'fortran_order': False, 'shape': (", rows, ", 5), }");
  // Data starts on a 64-byte boundary; the header ends in a newline (the format's rule).
  while ((kMagic.size() + 4 + header.size() + 1) % 64 != 0) header += ' ';
  header += '\n';
  std::string out(kMagic);
  out += '\x01';
  out += '\x00';
  out += char(header.size() & 0xff);
  out += char(header.size() >> 8);
  out += header;
  out.reserve(out.size() + rows * 5 * 8);
  for (std::size_t pass = 0; pass < passes.size(); ++pass) {
    for (std::size_t i = 0; i < passes[pass].t_s.size(); ++i) {
      const std::array<double, 5> row{double(pass), passes[pass].t_s[i], passes[pass].v[i][0], passes[pass].v[i][1],
                                      passes[pass].v[i][2]};
      out.append(reinterpret_cast<const char*>(row.data()), sizeof row);
    }
  }
  return out;
}

}  // namespace vt::acq
