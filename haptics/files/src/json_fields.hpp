#pragma once
// Strict JSON field access for the haptic file readers: every miss names the source and the path.
#include <string>

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

inline nlohmann::json parse(std::string_view text, const std::string& source) {
  checkJsonNesting(text, source, budget::kJsonDepth);  // the tree is copied and walked recursively
  nlohmann::json doc = nlohmann::json::parse(text, nullptr, false);
  if (doc.is_discarded()) fail(source, ": not valid JSON");
  if (!doc.is_object()) fail(source, ": the top level must be an object");
  return doc;
}

}  // namespace vt::haptics::files
