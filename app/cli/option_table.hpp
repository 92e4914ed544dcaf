#pragma once
// The one table of the command line: every command and every option, declared once. Parsing
// (cli::Args), each command's --help, `vtouching help`, the man page, bash completion and the
// option tables of docs/app.md all come from it (docs/app.md, "Options"). Constant data; any thread.
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace vt::cli {

/// How an option's value is written and checked.
enum class ValueKind { Flag, Text, Path, Number, Integer, Size, Choice };

/// One option, taken by one or more commands. The same name may appear in several entries when
/// its value or default differs between commands (each command takes each name at most once).
struct OptionSpec {
  std::string_view name;      ///< without the leading "--"
  std::string_view value;     ///< the value as help writes it ("FILE.gltf", "paper|texture|taxel"); empty for flags
  ValueKind kind = ValueKind::Flag;
  std::string_view fallback;  ///< the default; code that reads the option with a fallback must use this one
  std::string_view commands;  ///< the commands that take it, space-separated ("global": every command)
  std::string_view section;   ///< its group in --help and its table in docs/app.md (SectionSpec::key)
  std::string_view help;      ///< one line
  bool repeatable = false;    ///< may be given more than once (read with Args::values)
};

/// A group of options: a heading in --help and the man page, a table in docs/app.md.
struct SectionSpec {
  std::string_view key;
  std::string_view title;
};

/// One command: what it does and how it is called.
struct CommandSpec {
  std::string_view name;
  std::string_view summary;  ///< one line
  std::string_view forms;    ///< the arguments after the name, one synopsis per line
  std::string_view probes;   ///< per form, arguments that reach its option reading (`help --check`)
};

/// The whole command line.
struct OptionTable {
  std::span<const SectionSpec> sections;
  std::span<const CommandSpec> commands;
  std::span<const OptionSpec> options;
};

/// The vtouching command line (app/cli/option_table.cpp).
const OptionTable& optionTable();

/// True when `option` is taken by `command` (or by every command).
bool takes(const OptionSpec& option, std::string_view command);
/// The entry `command` reads for --name, or null when it does not take it.
const OptionSpec* findOption(const OptionTable& table, std::string_view command, std::string_view name);
/// Every entry named `name`, whichever command takes it.
std::vector<const OptionSpec*> entriesNamed(const OptionTable& table, std::string_view name);
/// The options `command` takes, in table order (global options last).
std::vector<const OptionSpec*> optionsOf(const OptionTable& table, std::string_view command);
const CommandSpec* findCommandSpec(const OptionTable& table, std::string_view name);
/// The non-empty parts of `text` between `separator`s.
std::vector<std::string_view> split(std::string_view text, char separator);
/// The lines of a '\n'-separated field (forms, probes); the words of a space-separated one.
std::vector<std::string_view> lines(std::string_view text);
std::vector<std::string_view> words(std::string_view text);

/// Empty when `value` is a valid value for `option` (by its kind and syntax), else why not.
std::string checkValue(const OptionSpec& option, std::string_view value);
/// The literal choices of a Choice or Text syntax ("sim|hid|hid:SERIAL|none" -> sim, hid, none).
std::vector<std::string> literalChoices(const OptionSpec& option);

}  // namespace vt::cli
