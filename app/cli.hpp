#pragma once
// Subcommand registry and the argument reader of the vtouching CLI (main thread only). Which
// options a command takes, their syntax and defaults come from the option table
// (cli/option_table.hpp); a command's code reads them by name.
#include <functional>
#include <optional>
#include <set>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "cli/option_table.hpp"

namespace vt::cli {

/// Thrown by Args::finish() in probe mode: every option has been read (`vtouching help --check`).
struct ProbeDone {};

/// The words after a command, split by the option table: `--name VALUE`, `--name=VALUE`,
/// `--flag`, and positionals. An option the command does not take, a missing value or a repeat of
/// a non-repeatable option is refused when constructed (vt::Error, one line naming it).
/// Reading an option the command does not take gives "absent" (shared readers serve several
/// commands); reading a name the table does not know, or a fallback that contradicts the
/// table's default, is a bug (std::logic_error).
class Args {
 public:
  Args(std::string command, std::vector<std::string> words, const OptionTable& table = optionTable());

  /// Value of `--name VALUE`, consumed; nullopt when absent.
  std::optional<std::string> value(std::string_view name);
  /// Every value of a repeatable option, in order, consumed (empty when absent).
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
  /// Throws vt::Error naming any option or argument left unread (call after reading all options).
  /// In probe mode throws ProbeDone instead.
  void finish() const;
  const std::string& command() const { return m_command; }

  /// Probe mode: finish() ends the command before it does anything (`help --check`).
  void setProbe() { m_probe = true; }
  /// The options this command's code has read so far (whether given or not).
  const std::set<std::string, std::less<>>& readOptions() const { return m_read; }

 private:
  struct Given {
    const OptionSpec* option;
    std::string value;
    bool used = false;
  };
  /// The table's entry for `name` (null when this command does not take it); notes the read.
  const OptionSpec* lookup(std::string_view name, bool wantsValue);
  /// The given occurrence of `name`, consumed (null when absent).
  Given* take(std::string_view name, bool wantsValue);
  /// A fallback in code must be the table's default when the table states one.
  void checkFallback(std::string_view name, const std::string& fallback);

  std::string m_command;
  const OptionTable& m_table;
  std::vector<Given> m_given;
  std::vector<std::pair<std::string, bool>> m_positionals;  // word, used
  std::set<std::string, std::less<>> m_read;
  bool m_probe = false;
};

struct Command {
  std::string_view name;
  int (*run)(Args& args);
};

/// Registers a subcommand (from a static initialiser in its file).
bool registerCommand(const Command& command);
const std::vector<Command>& commands();
const Command* findCommand(std::string_view name);

}  // namespace vt::cli

/// Defines and registers a subcommand: VT_COMMAND(render) { ... return 0; }. Its summary, forms
/// and options are in the option table (app/cli/option_table.cpp).
#define VT_COMMAND(NAME)                                                                 \
  static int vtCommand_##NAME(::vt::cli::Args& args);                                    \
  [[maybe_unused]] static const bool vtCommandRegistered_##NAME =                        \
      ::vt::cli::registerCommand({#NAME, &vtCommand_##NAME});                             \
  static int vtCommand_##NAME(::vt::cli::Args& args)
