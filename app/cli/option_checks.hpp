#pragma once
// Checks that keep the option table true: against the commands' code (`vtouching help --check`)
// and against the command lines the documentation cites (tests/app/cli_docs_tests.cpp).
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "cli.hpp"

namespace vt::cli {

/// The table's own consistency (every command and section named exists, no command takes a name
/// twice, defaults are valid values, one-line help) and, for `commands`: each is in the table and
/// vice versa; its help lists exactly the options it takes; run in probe mode on every form of
/// the table, its code reads every option the table gives it. One line per problem; empty = fine.
std::vector<std::string> checkOptionTable(const OptionTable& table, std::span<const Command> commands);

/// A command line cited in a markdown file.
struct CitedCommand {
  int line = 0;      ///< 1-based line where it starts
  std::string text;  ///< as written (continuation lines joined, markdown escapes undone)
  bool runnable = true;  ///< a line of a code block (else an inline span of prose)
};

/// Every vtouching command line in `markdown`: lines of fenced code blocks that run `vtouching`
/// (bare or a path ending in /vtouching), and inline code spans that do or that start with a
/// command name followed by an option (`render --trajectory`).
std::vector<CitedCommand> citedCommands(const OptionTable& table, std::string_view markdown);

/// Empty when `line` is a valid vtouching command line for `table`: the command exists, it takes
/// every option given, and every value that is not a placeholder (FILE, WxH, a|b) parses; in
/// prose (not `runnable`) the last option may go without its value. Else the problem.
std::string checkCitedCommand(const OptionTable& table, std::string_view line, bool runnable = true);

}  // namespace vt::cli
