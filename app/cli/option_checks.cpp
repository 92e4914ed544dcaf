#include "cli/option_checks.hpp"

#include <algorithm>
#include <cctype>
#include <set>

#include "cli/help_text.hpp"
#include "vt/core/error.hpp"

namespace vt::cli {
namespace {

void checkTableItself(const OptionTable& table, std::vector<std::string>& problems) {
  std::set<std::string, std::less<>> sections;
  for (const SectionSpec& s : table.sections) sections.emplace(s.key);
  std::set<std::pair<std::string, std::string>> seen;
  for (const OptionSpec& o : table.options) {
    if (!sections.count(o.section)) problems.push_back(str("--", o.name, ": no section '", o.section, "'"));
    if (o.help.empty() || o.help.find('\n') != std::string_view::npos) problems.push_back(str("--", o.name, ": help must be one line"));
    if ((o.kind == ValueKind::Flag) != o.value.empty()) problems.push_back(str("--", o.name, ": a flag has no value, an option has one"));
    if (!o.fallback.empty()) {
      if (const std::string why = checkValue(o, o.fallback); !why.empty()) problems.push_back(str("default of ", why));
    }
    if (o.commands == "global") continue;
    for (std::string_view c : words(o.commands)) {
      if (!findCommandSpec(table, c)) problems.push_back(str("--", o.name, ": no command '", c, "'"));
      if (!seen.emplace(std::string(c), std::string(o.name)).second) problems.push_back(str(c, " takes --", o.name, " twice"));
    }
  }
}

// The option names a command's help text shows (lines that start with "  --").
std::set<std::string, std::less<>> shownOptions(const std::string& help) {
  std::set<std::string, std::less<>> out;
  for (std::string_view line : lines(help)) {
    if (line.substr(0, 4) != "  --") continue;
    const std::size_t end = line.find_first_of(" \n", 4);
    out.emplace(line.substr(4, end == std::string_view::npos ? std::string_view::npos : end - 4));
  }
  return out;
}

// Runs `command` in probe mode on every form; the options its code read, or problems.
std::set<std::string, std::less<>> probeReads(const CommandSpec& spec, const Command& command, const OptionTable& table,
                                              std::vector<std::string>& problems) {
  std::set<std::string, std::less<>> read;
  std::vector<std::string_view> probes = lines(spec.probes);
  if (probes.empty()) probes.emplace_back();
  for (std::string_view probe : probes) {
    std::vector<std::string> argv;
    for (std::string_view w : words(probe)) argv.emplace_back(w);
    Args args(std::string(spec.name), argv, table);
    args.setProbe();
    try {
      command.run(args);
      problems.push_back(str(spec.name, " ", probe, ": returned without Args::finish()"));
    } catch (const ProbeDone&) {
    } catch (const std::exception& e) {
      problems.push_back(str(spec.name, " ", probe, ": failed before reading its options: ", e.what()));
    }
    read.insert(args.readOptions().begin(), args.readOptions().end());
  }
  return read;
}

}  // namespace

std::vector<std::string> checkOptionTable(const OptionTable& table, std::span<const Command> commands) {
  std::vector<std::string> problems;
  checkTableItself(table, problems);
  for (const CommandSpec& spec : table.commands) {
    const auto command = std::find_if(commands.begin(), commands.end(), [&](const Command& c) { return c.name == spec.name; });
    if (command == commands.end()) {
      problems.push_back(str("the table has a command '", spec.name, "' that no VT_COMMAND defines"));
      continue;
    }
    std::set<std::string, std::less<>> takes;
    for (const OptionSpec* o : optionsOf(table, spec.name)) takes.emplace(o->name);
    if (shownOptions(commandHelp(table, spec)) != takes) problems.push_back(str(spec.name, ": --help does not list exactly its options"));
    const auto read = probeReads(spec, *command, table, problems);
    for (const OptionSpec* o : optionsOf(table, spec.name)) {
      if (o->commands != "global" && !read.count(o->name)) {
        problems.push_back(str(spec.name, " takes --", o->name, " (the table) but its code never reads it"));
      }
    }
  }
  for (const Command& c : commands) {
    if (!findCommandSpec(table, c.name)) problems.push_back(str("VT_COMMAND(", c.name, ") is not in the option table"));
  }
  return problems;
}

namespace {

bool isVtouching(std::string_view token) {
  return token == "vtouching" || (token.size() > 10 && token.substr(token.size() - 10) == "/vtouching" &&
                                  token.find('=') == std::string_view::npos);
}

// Where the vtouching program is the word that runs (not the value of another program's
// option, as in `netns-session.sh --bin build/app/vtouching`); words.size() when nowhere.
std::size_t programWord(const std::vector<std::string>& words) {
  for (std::size_t i = 0; i < words.size(); ++i) {
    const bool optionValue = i > 0 && words[i - 1].rfind("--", 0) == 0 && words[i - 1].find('=') == std::string::npos;
    if (isVtouching(words[i]) && !optionValue) return i;
  }
  return words.size();
}

std::vector<std::string> tokens(std::string_view text) {
  // "[--overlay|--stereo]" is two alternatives.
  std::string line(text);
  for (std::size_t at = line.find("|--"); at != std::string::npos; at = line.find("|--", at + 4)) line.replace(at, 1, " | ");
  std::vector<std::string> out;
  std::string current;
  for (char c : line) {
    if (std::isspace(static_cast<unsigned char>(c))) {
      if (!current.empty()) out.push_back(std::move(current));
      current.clear();
    } else if (c != '"' && c != '\'') {
      current += c;
    }
  }
  if (!current.empty()) out.push_back(std::move(current));
  return out;
}

// Synopsis brackets and prose punctuation around a word.
std::string trimmed(std::string word) {
  while (!word.empty() && (word.front() == '[' || word.front() == '(')) word.erase(word.begin());
  while (!word.empty() && std::string_view("]),;.").find(word.back()) != std::string_view::npos) word.pop_back();
  return word;
}

// FILE, WxH, a|b, <x>, [...], $n: a value (or command) written as a pattern.
bool placeholder(std::string_view value) {
  return std::any_of(value.begin(), value.end(), [](char c) { return std::isupper(static_cast<unsigned char>(c)); }) ||
         value.find_first_of("|<[{$") != std::string_view::npos || value.find("...") != std::string_view::npos;
}

bool endsCommand(const std::vector<std::string>& words, std::size_t i) {
  const std::string& w = words[i];
  if (w == "#" || w == ";" || w == "&&" || w == "||" || w == "&" || w[0] == '>' || w.rfind("2>", 0) == 0) return true;
  // A pipe ends the command unless it separates alternatives in a synopsis ("--a | --b").
  return w == "|" && (i + 1 >= words.size() || trimmed(words[i + 1]).rfind("--", 0) != 0);
}

}  // namespace

std::string checkCitedCommand(const OptionTable& table, std::string_view line, bool runnable) {
  const std::vector<std::string> words = tokens(line);
  std::size_t i = programWord(words);
  i = i < words.size() ? i + 1 : 0;
  if (i < words.size() && (words[i] == "--version" || words[i] == "version")) return "";
  std::string command = "run";
  if (i < words.size() && words[i][0] != '-' && words[i][0] != '[' && !endsCommand(words, i)) {
    command = words[i++];
    if (placeholder(command)) return "";  // "vtouching COMMAND --help"
    if (!findCommandSpec(table, command)) return str("no command '", command, "'");
  }
  for (; i < words.size() && !endsCommand(words, i); ++i) {
    const std::string word = trimmed(words[i]);
    if (word.rfind("--", 0) != 0 || word.size() < 3) continue;  // positionals, alternatives, prose
    const std::size_t eq = word.find('=');
    const std::string name = word.substr(2, eq == std::string::npos ? std::string::npos : eq - 2);
    const OptionSpec* option = findOption(table, command, name);
    if (!option) return str("vtouching ", command, " does not take --", name);
    if (option->kind == ValueKind::Flag) continue;
    std::string value;
    if (eq != std::string::npos) value = word.substr(eq + 1);
    else if (i + 1 < words.size() && !endsCommand(words, i + 1) && trimmed(words[i + 1]).rfind("--", 0) != 0) value = words[++i];
    // Prose names a mode or an option (`render --trajectory`): its last option may go without a value.
    if (value.empty() && !runnable && (i + 1 >= words.size() || endsCommand(words, i + 1))) continue;
    if (value.empty()) return str("vtouching ", command, " --", name, " needs a value");
    if (placeholder(value)) continue;
    value = trimmed(value);
    if (const std::string why = checkValue(*option, value); !why.empty()) return str("vtouching ", command, ": ", why);
  }
  return "";
}

std::vector<CitedCommand> citedCommands(const OptionTable& table, std::string_view markdown) {
  std::vector<CitedCommand> out;
  auto cites = [&](std::string_view text) {
    const auto ws = tokens(text);
    if (programWord(ws) < ws.size()) return true;
    return ws.size() >= 2 && findCommandSpec(table, ws[0]) && ws[1].rfind("--", 0) == 0;
  };
  bool fenced = false;
  int lineNumber = 0, spanLine = 0;
  std::string pending;  // a fenced line continued with a backslash
  std::string span;
  bool inSpan = false;
  for (std::size_t at = 0; at <= markdown.size();) {
    const std::size_t end = std::min(markdown.find('\n', at), markdown.size());
    const std::string_view line = markdown.substr(at, end - at);
    at = end + 1;
    ++lineNumber;
    if (line.substr(0, 3) == "```") {
      fenced = !fenced;
      continue;
    }
    if (fenced) {
      if (!line.empty() && line.back() == '\\') {
        if (pending.empty()) spanLine = lineNumber;
        pending += std::string(line.substr(0, line.size() - 1)) + " ";
        continue;
      }
      const int start = pending.empty() ? lineNumber : spanLine;
      const std::string full = pending + std::string(line);
      pending.clear();
      if (cites(full)) out.push_back({start, full, true});
      continue;
    }
    // Inline code spans may run over a line break.
    for (std::size_t k = 0; k < line.size(); ++k) {
      if (line[k] != '`') {
        if (inSpan) span += line[k];
        continue;
      }
      if (k + 1 < line.size() && line[k + 1] == '`') {  // `` ... `` spans are literal text, not commands
        ++k;
        continue;
      }
      if (!inSpan) {
        inSpan = true, span.clear(), spanLine = lineNumber;
        continue;
      }
      inSpan = false;
      std::string text;
      for (std::size_t j = 0; j < span.size(); ++j) {
        if (span[j] == '\\' && j + 1 < span.size() && span[j + 1] == '|') continue;  // table escape of '|'
        text += span[j];
      }
      if (cites(text)) out.push_back({spanLine, text, false});
    }
    if (inSpan) span += ' ';
  }
  return out;
}

}  // namespace vt::cli
