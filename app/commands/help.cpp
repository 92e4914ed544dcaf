// `vtouching help [COMMAND]`, `help --man`, `help --check` and `vtouching completion bash`: the
// option table shown to people, to man and to the shell (app/cli/).
#include <cstdio>

#include "cli.hpp"
#include "cli/help_text.hpp"
#include "cli/option_checks.hpp"
#include "vt/core/error.hpp"

VT_COMMAND(help) {
  const bool man = args.flag("man");
  const bool check = args.flag("check");
  const auto topics = args.positionals();
  args.finish();
  const vt::cli::OptionTable& table = vt::cli::optionTable();
  if (man) {
    std::fputs(vt::cli::manPage(table, VT_VERSION).c_str(), stdout);
    return 0;
  }
  if (check) {
    const auto problems = vt::cli::checkOptionTable(table, vt::cli::commands());
    for (const std::string& problem : problems) std::printf("option table: %s\n", problem.c_str());
    std::printf("option table: %zu commands, %zu options, %zu problems\n", table.commands.size(), table.options.size(),
                problems.size());
    return problems.empty() ? 0 : 1;
  }
  if (topics.empty()) {
    std::fputs(vt::cli::overviewHelp(table).c_str(), stdout);
    return 0;
  }
  if (topics.size() > 1) vt::fail("help: one COMMAND at a time");
  const vt::cli::CommandSpec* command = vt::cli::findCommandSpec(table, topics[0]);
  if (!command) vt::fail("help: no command '", topics[0], "' (vtouching help lists them)");
  std::fputs(vt::cli::commandHelp(table, *command).c_str(), stdout);
  return 0;
}

VT_COMMAND(completion) {
  const auto shells = args.positionals();
  args.finish();
  if (shells.size() != 1 || shells[0] != "bash") vt::fail("completion: bash is the one shell supported (vtouching completion bash)");
  std::fputs(vt::cli::bashCompletion(vt::cli::optionTable()).c_str(), stdout);
  return 0;
}
