#include "cli.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <stdexcept>
#include <type_traits>

#include "vt/core/error.hpp"

namespace vt::cli {

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

std::pair<int, int> parseSize(const std::string& command, std::string_view name, const std::string& text) {
  const auto x = text.find('x');
  if (x == std::string::npos) fail(command, ": option --", name, " expects WxH, got '", text, "'");
  const int w = parseNumber<int>(command, name, text.substr(0, x));
  const int h = parseNumber<int>(command, name, text.substr(x + 1));
  if (w <= 0 || h <= 0 || w > 16384 || h > 16384) fail(command, ": option --", name, " size ", text, " out of range 1..16384");
  return {w, h};
}

// The table's default, when it states one, is the only default: code that falls back to another
// value is a bug the moment it runs (and `vtouching help --check` runs every command's reading).
template <class T, class Parse>
void requireTableDefault(const std::string& command, const OptionSpec* option, const T& fallback, Parse parse) {
  if (!option || option->fallback.empty()) return;
  const T declared = parse(std::string(option->fallback));
  bool same = declared == fallback;
  if constexpr (std::is_floating_point_v<T>) same = std::abs(declared - fallback) <= 1e-9 * std::max(1.0, std::abs(declared));
  if (!same) {
    throw std::logic_error(str("option table: ", command, " --", option->name, " defaults to '", option->fallback,
                               "' in app/cli/option_table.cpp but to another value in the code"));
  }
}

}  // namespace

Args::Args(std::string command, std::vector<std::string> words, const OptionTable& table)
    : m_command(std::move(command)), m_table(table) {
  for (std::size_t i = 0; i < words.size(); ++i) {
    const std::string& word = words[i];
    if (word.size() < 3 || word.rfind("--", 0) != 0) {
      m_positionals.emplace_back(word, false);
      continue;
    }
    const std::size_t eq = word.find('=');
    const std::string name = word.substr(2, eq == std::string::npos ? std::string::npos : eq - 2);
    const OptionSpec* option = findOption(m_table, m_command, name);
    if (!option) {
      std::string takers;
      for (const OptionSpec* other : entriesNamed(m_table, name)) {
        for (std::string_view c : cli::words(other->commands)) takers += str(takers.empty() ? "" : ", ", c);
      }
      if (takers.empty()) fail(m_command, ": unknown option '--", name, "' (see vtouching help ", m_command, ")");
      fail(m_command, ": option --", name, " is for ", takers, ", not ", m_command, " (see vtouching help ", m_command, ")");
    }
    std::string value;
    if (option->kind == ValueKind::Flag) {
      if (eq != std::string::npos) fail(m_command, ": option --", name, " takes no value");
    } else if (eq != std::string::npos) {
      value = word.substr(eq + 1);
    } else {
      if (i + 1 >= words.size()) fail(m_command, ": option --", name, " needs a value");
      value = words[++i];
    }
    const bool repeated = std::any_of(m_given.begin(), m_given.end(), [&](const Given& g) { return g.option == option; });
    if (repeated && !option->repeatable) fail(m_command, ": option --", name, " given more than once");
    m_given.push_back({option, std::move(value)});
  }
}

const OptionSpec* Args::lookup(std::string_view name, bool wantsValue) {
  const OptionSpec* option = findOption(m_table, m_command, name);
  if (!option) {
    if (entriesNamed(m_table, name).empty()) {
      throw std::logic_error(str("option table: ", m_command, " reads --", name, ", which no entry declares"));
    }
    return nullptr;  // another command's option: absent here
  }
  if ((option->kind == ValueKind::Flag) == wantsValue) {
    throw std::logic_error(str("option table: ", m_command, " reads --", name, wantsValue ? " as a value" : " as a flag",
                               " but the table says otherwise"));
  }
  m_read.emplace(name);
  return option;
}

Args::Given* Args::take(std::string_view name, bool wantsValue) {
  const OptionSpec* option = lookup(name, wantsValue);
  for (Given& given : m_given) {
    if (given.option == option && !given.used) {
      given.used = true;
      return &given;
    }
  }
  return nullptr;
}

std::vector<std::string> Args::values(std::string_view name) {
  std::vector<std::string> found;
  while (Given* given = take(name, true)) found.push_back(given->value);
  return found;
}

std::optional<std::string> Args::value(std::string_view name) {
  std::vector<std::string> found = values(name);
  // A second occurrence is a mistake either way (which one wins?).
  if (found.size() > 1) fail(m_command, ": option --", name, " given more than once");
  if (found.empty()) return std::nullopt;
  return std::move(found.front());
}

bool Args::flag(std::string_view name) { return take(name, false) != nullptr; }

std::string Args::valueOr(std::string_view name, std::string fallback) {
  requireTableDefault(m_command, findOption(m_table, m_command, name), fallback, [](std::string s) { return s; });
  auto v = value(name);
  return v ? *v : std::move(fallback);
}

int Args::intOr(std::string_view name, int fallback) {
  requireTableDefault(m_command, findOption(m_table, m_command, name), fallback,
                      [&](const std::string& s) { return parseNumber<int>(m_command, name, s); });
  auto v = value(name);
  return v ? parseNumber<int>(m_command, name, *v) : fallback;
}

double Args::doubleOr(std::string_view name, double fallback) {
  requireTableDefault(m_command, findOption(m_table, m_command, name), fallback,
                      [&](const std::string& s) { return parseNumber<double>(m_command, name, s); });
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
  requireTableDefault(m_command, findOption(m_table, m_command, name), fallback,
                      [&](const std::string& s) { return parseSize(m_command, name, s); });
  auto v = value(name);
  return v ? parseSize(m_command, name, *v) : fallback;
}

std::vector<std::string> Args::positionals() {
  std::vector<std::string> out;
  for (auto& [word, used] : m_positionals) {
    if (used) continue;
    used = true;
    out.push_back(word);
  }
  return out;
}

void Args::finish() const {
  if (m_probe) throw ProbeDone{};
  for (const Given& given : m_given) {
    if (!given.used) fail(m_command, ": option --", given.option->name, " does not apply here (see vtouching help ", m_command, ")");
  }
  for (const auto& [word, used] : m_positionals) {
    if (!used) fail(m_command, ": unexpected argument '", word, "' (see vtouching help ", m_command, ")");
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
