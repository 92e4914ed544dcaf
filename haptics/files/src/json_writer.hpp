#pragma once
// Writes the haptic files' JSON straight into a string, without a DOM: an export takes the
// output's size and little more (a DOM took ~7 times the text). Numbers are printed in their
// shortest form that reads back exactly (std::to_chars).
#include <charconv>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

namespace vt::haptics::files {

class JsonWriter {
 public:
  explicit JsonWriter(std::string& out) : m_out(out) {}

  JsonWriter& beginObject() { return open('{'); }
  JsonWriter& endObject() { return close('}'); }
  JsonWriter& beginArray() { return open('['); }
  JsonWriter& endArray() { return close(']'); }
  /// The next member's name (inside an object).
  JsonWriter& key(std::string_view name) {
    separate();
    m_out += '"';
    m_out += name;
    m_out += "\":";
    m_afterKey = true;
    return *this;
  }
  JsonWriter& value(double v) { return number(v); }
  JsonWriter& value(float v) { return number(v); }
  JsonWriter& value(std::int64_t v) { return number(v); }
  JsonWriter& value(std::uint64_t v) { return number(v); }
  JsonWriter& value(int v) { return number(std::int64_t(v)); }
  JsonWriter& value(std::string_view s) {
    separate();
    m_out += nlohmann::json(s).dump();  // escapes
    return *this;
  }
  JsonWriter& value(const char* s) { return value(std::string_view(s)); }
  /// `"name": value` in one call.
  template <typename T>
  JsonWriter& member(std::string_view name, const T& v) {
    return key(name).value(v);
  }

 private:
  void separate() {
    if (m_afterKey) {
      m_afterKey = false;
      return;
    }
    if (!m_first.empty()) {
      if (!m_first.back()) m_out += ',';
      m_first.back() = false;
    }
  }
  JsonWriter& open(char c) {
    separate();
    m_out += c;
    m_first.push_back(true);
    return *this;
  }
  JsonWriter& close(char c) {
    m_first.pop_back();
    m_out += c;
    return *this;
  }
  template <typename T>
  JsonWriter& number(T v) {
    separate();
    char buffer[32];
    const auto [end, ec] = std::to_chars(buffer, buffer + sizeof buffer, v);
    m_out.append(std::string_view(buffer, std::size_t(end - buffer)));
    return *this;
  }

  std::string& m_out;
  std::vector<bool> m_first;
  bool m_afterKey = false;
};

}  // namespace vt::haptics::files
