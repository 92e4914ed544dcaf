#pragma once
// Strict JSON access for the haptic file readers: every miss names the source and the path. The
// documents are parsed through a SAX handler that stores the bulk of a file, arrays of flat
// records (HJIF keyframes, AHAP control points, .haptic breakpoints), as packed numbers: a file
// of N bytes takes well under N bytes once parsed (docs/haptic-files.md, "Memory").
#include <cmath>
#include <cstring>
#include <initializer_list>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

#include "vt/core/budgets.hpp"
#include "vt/core/error.hpp"
#include "vt/core/text_input.hpp"

namespace vt::haptics::files {

inline const nlohmann::json& field(const nlohmann::json& object, const char* key, const std::string& where) {
  if (!object.is_object()) fail(where, " must be an object");
  const auto it = object.find(key);
  if (it == object.end()) fail(where, ".", key, " is missing");
  return *it;
}

inline double number(const nlohmann::json& object, const char* key, const std::string& where, double lo, double hi) {
  const nlohmann::json& v = field(object, key, where);
  if (!v.is_number() || !(v.get<double>() >= lo && v.get<double>() <= hi)) {
    fail(where, ".", key, " must be a number in [", lo, ", ", hi, "]");
  }
  return v.get<double>();
}

inline const nlohmann::json& array(const nlohmann::json& object, const char* key, const std::string& where) {
  const nlohmann::json& v = field(object, key, where);
  if (!v.is_array()) fail(where, ".", key, " must be an array");
  return v;
}

inline std::string text(const nlohmann::json& object, const char* key, const std::string& where) {
  const nlohmann::json& v = field(object, key, where);
  if (!v.is_string()) fail(where, ".", key, " must be a string");
  return v.get<std::string>();
}

/// An array of flat records packed at parse time: the columns the reader named, one double each.
struct RecordArray {
  const char* key;                           // the member holding the array ("keyframes")
  std::initializer_list<const char*> columns;  // members read from each record; others are skipped
};

/// Parses `text` (an object at the top level, nesting at most 64 deep); arrays under a key listed
/// in `packed` become records readable through Records. Throws vt::Error naming `source`.
nlohmann::json parse(std::string_view text, const std::string& source, std::initializer_list<RecordArray> packed = {});

/// The records of a packed array: a missing member reads as NaN, one that is not a number as
/// infinity, so the range checks below name both.
class Records {
 public:
  Records(const nlohmann::json& object, const char* key, std::size_t columns, const std::string& where);
  std::size_t size() const { return m_rows; }
  bool has(std::size_t row, std::size_t column) const { return !std::isnan(raw(row, column)); }
  /// The value, or vt::Error "WHERE.KEY[row].NAME is missing / must be a number in [lo, hi]".
  double number(std::size_t row, std::size_t column, const char* name, double lo, double hi) const;
  std::string where(std::size_t row) const;

 private:
  double raw(std::size_t row, std::size_t column) const {
    double v;
    std::memcpy(&v, m_bytes->data() + (row * m_columns + column) * sizeof(double), sizeof v);
    return v;
  }
  const std::vector<std::uint8_t>* m_bytes = nullptr;
  std::size_t m_columns = 0, m_rows = 0;
  std::string m_where;
};

}  // namespace vt::haptics::files
