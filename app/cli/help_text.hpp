#pragma once
// Everything the option table is shown as: each command's --help, `vtouching help`, the man
// page, docs/app.md's option tables and the bash completion script. Pure functions of the table.
#include <string>
#include <string_view>

#include "cli/option_table.hpp"

namespace vt::cli {

/// `vtouching help COMMAND` / `vtouching COMMAND --help`: forms, summary, options by section.
std::string commandHelp(const OptionTable& table, const CommandSpec& command);
/// `vtouching help`: every command with its summary.
std::string overviewHelp(const OptionTable& table);
/// The man page (troff, section 1) for `vtouching help --man`.
std::string manPage(const OptionTable& table, std::string_view version);
/// The markdown table of one section's options (docs/app.md holds one per section).
std::string markdownTable(const OptionTable& table, std::string_view section);
/// A bash completion script for `vtouching completion bash`.
std::string bashCompletion(const OptionTable& table);

/// "--name VALUE" as help writes it.
std::string optionSynopsis(const OptionSpec& option);

}  // namespace vt::cli
