#pragma once
// Subcommand registry and a small argument parser for the vtouching CLI (main thread only).
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace vt::cli {

/// Command-line options of one subcommand: `--name value`, `--flag`, and positionals.
class Args {
 public:
  Args(std::string command, std::vector<std::string> words);

  /// Value of `--name VALUE` (or `--name=VALUE`), consumed; nullopt when absent; throws when
  /// given twice.
  std::optional<std::string> value(std::string_view name);
  /// Every `--name VALUE` of a repeatable option, in order, consumed (empty when absent).
  std::vector<std::string> values(std::string_view name);
  /// `--name` present? consumed.
  bool flag(std::string_view name);
  std::string valueOr(std::string_view name, std::string fallback);
  int intOr(std::string_view name, int fallback);
  /// Finite numbers only (NaN and infinity are refused, naming the option).
  double doubleOr(std::string_view name, double fallback);
  /// Same, refused outside [lo, hi] with a message naming the option and the range.
  int intIn(std::string_view name, int fallback, int lo, int hi);
  double doubleIn(std::string_view name, double fallback, double lo, double hi);
  /// Parses `WxH` (e.g. 1280x720).
  std::pair<int, int> sizeOr(std::string_view name, std::pair<int, int> fallback);
  /// Remaining words that are not options, in order; consumed.
  std::vector<std::string> positionals();
  /// Throws vt::Error naming any option left unconsumed (call after reading all options).
  void finish() const;
  const std::string& command() const { return m_command; }

 private:
  std::string m_command;
  std::vector<std::string> m_words;
  std::vector<bool> m_used;
};

struct Command {
  std::string_view name;
  std::string_view usage;    // one line: "render --out DIR [--size WxH] ..."
  std::string_view summary;  // one line
  int (*run)(Args& args);
};

/// Registers a subcommand (from a static initialiser in its file).
bool registerCommand(const Command& command);
const std::vector<Command>& commands();
const Command* findCommand(std::string_view name);

}  // namespace vt::cli

/// Defines and registers a subcommand: VT_COMMAND(render, "usage", "summary") { ... return 0; }
#define VT_COMMAND(NAME, USAGE, SUMMARY)                                                   \
  static int vtCommand_##NAME(::vt::cli::Args& args);                                    \
  [[maybe_unused]] static const bool vtCommandRegistered_##NAME =                        \
      ::vt::cli::registerCommand({#NAME, USAGE, SUMMARY, &vtCommand_##NAME});             \
  static int vtCommand_##NAME(::vt::cli::Args& args)
