#include "cli.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <type_traits>

#include "vt/core/error.hpp"

namespace vt::cli {

Args::Args(std::string command, std::vector<std::string> words)
    : m_command(std::move(command)), m_words(std::move(words)), m_used(m_words.size(), false) {}

std::vector<std::string> Args::values(std::string_view name) {
  const std::string option = "--" + std::string(name);
  std::vector<std::string> found;
  for (std::size_t i = 0; i < m_words.size(); ++i) {
    if (m_used[i]) continue;
    const bool separate = m_words[i] == option, joined = m_words[i].rfind(option + "=", 0) == 0;
    if (!separate && !joined) continue;
    if (separate && i + 1 >= m_words.size()) fail(m_command, ": option ", option, " needs a value");
    m_used[i] = true;
    if (separate) m_used[++i] = true;
    found.push_back(separate ? m_words[i] : m_words[i].substr(option.size() + 1));
  }
  return found;
}

std::optional<std::string> Args::value(std::string_view name) {
  std::vector<std::string> found = values(name);
  // A second occurrence is a mistake either way (which one wins?): say so instead of
  // leaving it to finish() as an "unknown option".
  if (found.size() > 1) fail(m_command, ": option --", name, " given more than once");
  if (found.empty()) return std::nullopt;
  return std::move(found.front());
}

bool Args::flag(std::string_view name) {
  const std::string option = "--" + std::string(name);
  bool found = false;
  for (std::size_t i = 0; i < m_words.size(); ++i) {
    if (m_used[i] || m_words[i] != option) continue;
    if (found) fail(m_command, ": option ", option, " given more than once");
    m_used[i] = found = true;
  }
  return found;
}

std::string Args::valueOr(std::string_view name, std::string fallback) {
  auto v = value(name);
  return v ? *v : std::move(fallback);
}

namespace {
template <class T>
T parseNumber(const std::string& command, std::string_view name, const std::string& text) {
  T out{};
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), out);
  if (ec == std::errc::result_out_of_range) fail(command, ": option --", name, " value '", text, "' is out of range");
  if (ec != std::errc() || end != text.data() + text.size()) {
    fail(command, ": option --", name, " expects a number, got '", text, "'");
  }
  if constexpr (std::is_floating_point_v<T>) {
    // from_chars accepts "nan" and "inf"; no option means either.
    if (!std::isfinite(out)) fail(command, ": option --", name, " must be a finite number, got '", text, "'");
  }
  return out;
}
}  // namespace

int Args::intOr(std::string_view name, int fallback) {
  auto v = value(name);
  return v ? parseNumber<int>(m_command, name, *v) : fallback;
}

double Args::doubleOr(std::string_view name, double fallback) {
  auto v = value(name);
  return v ? parseNumber<double>(m_command, name, *v) : fallback;
}

int Args::intIn(std::string_view name, int fallback, int lo, int hi) {
  const int v = intOr(name, fallback);
  if (v < lo || v > hi) fail(m_command, ": option --", name, " ", v, " out of range ", lo, "..", hi);
  return v;
}

double Args::doubleIn(std::string_view name, double fallback, double lo, double hi) {
  const double v = doubleOr(name, fallback);
  if (!(v >= lo && v <= hi)) fail(m_command, ": option --", name, " ", v, " out of range ", lo, "..", hi);
  return v;
}

std::pair<int, int> Args::sizeOr(std::string_view name, std::pair<int, int> fallback) {
  auto v = value(name);
  if (!v) return fallback;
  const auto x = v->find('x');
  if (x == std::string::npos) fail(m_command, ": option --", name, " expects WxH, got '", *v, "'");
  const int w = parseNumber<int>(m_command, name, v->substr(0, x));
  const int h = parseNumber<int>(m_command, name, v->substr(x + 1));
  if (w <= 0 || h <= 0 || w > 16384 || h > 16384) {
    fail(m_command, ": option --", name, " size ", *v, " out of range 1..16384");
  }
  return {w, h};
}

std::vector<std::string> Args::positionals() {
  std::vector<std::string> out;
  for (std::size_t i = 0; i < m_words.size(); ++i) {
    if (!m_used[i] && m_words[i].rfind("--", 0) != 0) {
      m_used[i] = true;
      out.push_back(m_words[i]);
    }
  }
  return out;
}

void Args::finish() const {
  for (std::size_t i = 0; i < m_words.size(); ++i) {
    if (!m_used[i]) fail(m_command, ": unknown option or argument '", m_words[i], "' (see vtouching help)");
  }
}

namespace {
std::vector<Command>& registry() {
  static std::vector<Command> commands;
  return commands;
}
}  // namespace

bool registerCommand(const Command& command) {
  auto& all = registry();
  all.push_back(command);
  std::sort(all.begin(), all.end(), [](const Command& a, const Command& b) { return a.name < b.name; });
  return true;
}

const std::vector<Command>& commands() { return registry(); }

const Command* findCommand(std::string_view name) {
  for (const Command& c : registry()) {
    if (c.name == name) return &c;
  }
  return nullptr;
}

}  // namespace vt::cli
