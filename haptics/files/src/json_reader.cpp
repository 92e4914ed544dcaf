// The haptic files' JSON parser: nlohmann's SAX parser (no recursion) feeding a DOM whose bulk
// record arrays are packed as doubles (json_fields.hpp says why).
#include <limits>

#include "json_fields.hpp"

namespace vt::haptics::files {
namespace {

using nlohmann::json;

constexpr std::size_t kMaxDepth = 64;
// JSON values kept as a DOM (packed records do not count): bounds the DOM at a few hundred MB
// whatever the file holds. AHAP's 100000 events take about a million.
constexpr std::size_t kMaxDomValues = 2'000'000;

class PackingHandler {
 public:
  PackingHandler(const std::string& source, std::initializer_list<RecordArray> packed) : m_source(source), m_packed(packed) {}

  json& root() { return m_root; }

  bool null() { return value(json()); }
  bool boolean(bool v) { return value(json(v)); }
  bool number_integer(json::number_integer_t v) { return m_record ? recordValue(double(v)) : value(json(v)); }
  bool number_unsigned(json::number_unsigned_t v) { return m_record ? recordValue(double(v)) : value(json(v)); }
  bool number_float(json::number_float_t v, const std::string&) { return m_record ? recordValue(v) : value(json(v)); }
  bool string(std::string& v) { return value(json(std::move(v))); }
  bool binary(json::binary_t&) { return value(json()); }

  bool start_object(std::size_t) {
    if (m_record) return startRecordObject();
    return open(json::object());
  }
  bool end_object() {
    if (m_record) return endRecordObject();
    m_stack.pop_back();
    --m_depth;
    return true;
  }
  bool start_array(std::size_t) {
    if (m_record) return skipOrMark();
    for (const RecordArray& packed : m_packed) {
      if (m_key == packed.key && !m_stack.empty() && m_stack.back()->is_object()) {
        if (++m_depth > kMaxDepth) fail(m_source, ": nested more than ", kMaxDepth, " levels deep");
        m_record = &packed;
        m_slot = m_member;
        m_bytes.clear();
        m_rows = 0;
        m_recordDepth = 0;
        return true;
      }
    }
    return open(json::array());
  }
  bool end_array() {
    if (!m_record) {
      m_stack.pop_back();
      --m_depth;
      return true;
    }
    if (m_skip > 0) return --m_skip, --m_depth, true;
    *m_slot = json::binary(std::move(m_bytes));
    m_bytes = {};
    m_record = nullptr;
    --m_depth;
    return true;
  }
  bool key(std::string& k) {
    if (m_record) {
      if (m_skip == 0) m_path.resize(m_prefix.back()), m_path += k;
      return true;
    }
    m_key = k;
    m_member = &(*m_stack.back())[k];
    return true;
  }
  bool parse_error(std::size_t position, const std::string&, const nlohmann::detail::exception&) {
    fail(m_source, ": not valid JSON (at byte ", position, ")");
  }

 private:
  bool open(json&& v) {
    if (++m_depth > kMaxDepth) fail(m_source, ": nested more than ", kMaxDepth, " levels deep");
    m_stack.push_back(place(std::move(v)));
    return true;
  }
  json* place(json&& v) {
    if (++m_values > kMaxDomValues) fail(m_source, ": more than ", kMaxDomValues, " JSON values outside the bulk arrays");
    if (m_stack.empty()) {
      m_root = std::move(v);
      return &m_root;
    }
    if (m_stack.back()->is_array()) {
      m_stack.back()->push_back(std::move(v));
      return &m_stack.back()->back();
    }
    *m_member = std::move(v);
    return m_member;
  }
  bool value(json&& v) {
    if (m_record) return recordValue(std::numeric_limits<double>::infinity());
    place(std::move(v));
    return true;
  }

  // Inside a packed array: records are objects; members are matched by their dotted path.
  std::string rowWhere() const { return str(m_source, ": ", m_record->key, "[", m_rows, "]"); }
  bool startRecordObject() {
    if (m_skip > 0 || m_recordDepth >= 2) return skipOrMark();
    if (++m_depth > kMaxDepth) fail(m_source, ": nested more than ", kMaxDepth, " levels deep");
    if (m_recordDepth == 0) {
      m_bytes.resize(m_bytes.size() + m_record->columns.size() * sizeof(double));
      for (std::size_t c = 0; c < m_record->columns.size(); ++c) store(c, std::numeric_limits<double>::quiet_NaN());
      m_path.clear();
      m_prefix.assign(1, 0);
      m_found = false;
    } else {
      m_path += '.';
      m_prefix.push_back(m_path.size());
    }
    ++m_recordDepth;
    return true;
  }
  bool endRecordObject() {
    if (m_skip > 0) return --m_skip, --m_depth, true;
    --m_depth;
    if (--m_recordDepth > 0) {
      m_prefix.pop_back();  // the next key sets the path again
      return true;
    }
    // A record must hold a member the reader wants: a file cannot grow the packed table faster
    // than its own size.
    if (!m_found) fail(rowWhere(), " has none of the members read here");
    ++m_rows;
    return true;
  }
  bool skipOrMark() {
    if (m_recordDepth == 0 && m_skip == 0) fail(rowWhere(), " must be an object");
    if (m_skip == 0) recordValue(std::numeric_limits<double>::infinity());
    if (++m_depth > kMaxDepth) fail(m_source, ": nested more than ", kMaxDepth, " levels deep");
    ++m_skip;
    return true;
  }
  bool recordValue(double v) {
    if (m_skip > 0) return true;
    if (m_recordDepth == 0) fail(rowWhere(), " must be an object");
    std::size_t c = 0;
    for (const char* column : m_record->columns) {
      if (m_path == column) {
        store(c, v);
        m_found = true;
      }
      ++c;
    }
    return true;
  }
  void store(std::size_t column, double v) {
    std::memcpy(m_bytes.data() + m_bytes.size() - (m_record->columns.size() - column) * sizeof(double), &v, sizeof v);
  }

  const std::string& m_source;
  std::initializer_list<RecordArray> m_packed;
  json m_root;
  std::vector<json*> m_stack;
  json* m_member = nullptr;
  std::string m_key;
  std::size_t m_depth = 0, m_values = 0;
  // Packed-array state.
  const RecordArray* m_record = nullptr;
  json* m_slot = nullptr;
  std::vector<std::uint8_t> m_bytes;
  std::size_t m_rows = 0, m_recordDepth = 0, m_skip = 0;
  std::string m_path;
  std::vector<std::size_t> m_prefix;
  bool m_found = false;
};

}  // namespace

json parse(std::string_view text, const std::string& source, std::initializer_list<RecordArray> packed) {
  PackingHandler handler(source, packed);
  json::sax_parse(text.begin(), text.end(), &handler);
  if (!handler.root().is_object()) fail(source, ": the top level must be an object");
  return std::move(handler.root());
}

Records::Records(const json& object, const char* key, std::size_t columns, const std::string& where)
    : m_columns(columns), m_where(str(where, ".", key)) {
  const json& v = field(object, key, where);
  if (!v.is_binary()) fail(where, ".", key, " must be an array");
  m_bytes = &v.get_binary();
  m_rows = m_bytes->size() / (columns * sizeof(double));
}

std::string Records::where(std::size_t row) const { return str(m_where, "[", row, "]"); }

double Records::number(std::size_t row, std::size_t column, const char* name, double lo, double hi) const {
  const double v = raw(row, column);
  if (std::isnan(v)) fail(where(row), ".", name, " is missing");
  if (!(v >= lo && v <= hi)) fail(where(row), ".", name, " must be a number in [", lo, ", ", hi, "]");
  return v;
}

}  // namespace vt::haptics::files
