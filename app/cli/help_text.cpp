#include "cli/help_text.hpp"

#include <algorithm>
#include <map>
#include <vector>

#include "vt/core/error.hpp"

namespace vt::cli {
namespace {

constexpr std::size_t kHelpColumn = 32;
constexpr std::size_t kLineWidth = 100;

// `text` broken at spaces into lines of at most kLineWidth, each after the help column.
std::string wrapped(const std::string& text) {
  std::string out, line;
  for (std::string_view word : words(text)) {
    if (!line.empty() && kHelpColumn + line.size() + 1 + word.size() > kLineWidth) {
      out += line + "\n" + std::string(kHelpColumn, ' ');
      line.clear();
    }
    line += str(line.empty() ? "" : " ", word);
  }
  return out + line + "\n";
}

std::string defaultNote(const OptionSpec& option) {
  return option.fallback.empty() ? "" : str(" (default: ", option.fallback, ")");
}

std::string commaList(std::string_view spaceSeparated) {
  std::string out;
  for (std::string_view w : words(spaceSeparated)) out += str(out.empty() ? "" : ", ", w);
  return out;
}

// The options `command` takes in one section, in table order.
std::vector<const OptionSpec*> inSection(const std::vector<const OptionSpec*>& options, std::string_view section) {
  std::vector<const OptionSpec*> out;
  std::copy_if(options.begin(), options.end(), std::back_inserter(out),
               [&](const OptionSpec* o) { return o->section == section; });
  return out;
}

// troff: backslashes escaped, every hyphen a minus (options are typed), no line starting a request.
std::string roff(std::string_view text) {
  std::string out;
  for (char c : text) {
    if (c == '\\') out += "\\e";
    else if (c == '-') out += "\\-";
    else out += c;
  }
  if (!out.empty() && (out[0] == '.' || out[0] == '\'')) out.insert(0, "\\&");
  return out;
}

std::string markdownCode(std::string_view text) {
  std::string out = "`";
  for (char c : text) out += c == '|' ? std::string("\\|") : std::string(1, c);
  return out + "`";
}

}  // namespace

std::string optionSynopsis(const OptionSpec& option) {
  return option.value.empty() ? str("--", option.name) : str("--", option.name, " ", option.value);
}

std::string commandHelp(const OptionTable& table, const CommandSpec& command) {
  std::string out;
  const char* lead = "usage: ";
  for (std::string_view form : lines(command.forms)) {
    out += str(lead, "vtouching ", command.name, " ", form, "\n");
    lead = "       ";
  }
  out += str("\n", command.summary, "\n");
  const auto options = optionsOf(table, command.name);
  for (const SectionSpec& section : table.sections) {
    const auto group = inSection(options, section.key);
    if (group.empty()) continue;
    out += str("\n", section.title, ":\n");
    for (const OptionSpec* option : group) {
      std::string line = "  " + optionSynopsis(*option);
      line += line.size() + 2 <= kHelpColumn ? std::string(kHelpColumn - line.size(), ' ')
                                             : "\n" + std::string(kHelpColumn, ' ');
      out += line + wrapped(str(option->help, defaultNote(*option), option->repeatable ? " (repeatable)" : ""));
    }
  }
  return out;
}

std::string overviewHelp(const OptionTable& table) {
  std::string out = "usage: vtouching [COMMAND] [options]   (no COMMAND: run)\n\ncommands:\n";
  for (const CommandSpec& command : table.commands) {
    out += str("  ", command.name, std::string(command.name.size() < 11 ? 12 - command.name.size() : 1, ' '),
               command.summary, "\n");
  }
  out += "\nvtouching help COMMAND (or vtouching COMMAND --help): its forms and options with their defaults.\n"
         "global options: --log debug|info|warn|error|off, --help; vtouching --version: the version.\n"
         "docs/app.md (installed under share/doc/vtouching) explains every mode; man vtouching lists every option.\n";
  return out;
}

std::string manPage(const OptionTable& table, std::string_view version) {
  std::string out = str(".TH VTOUCHING 1 \"\" \"vtouching ", version, "\" \"User Commands\"\n",
                        ".SH NAME\nvtouching \\- spatially aligned visual\\-tactile perception in VR\n",
                        ".SH SYNOPSIS\n.B vtouching\n[\\fICOMMAND\\fR] [\\fIoptions\\fR]\n",
                        ".SH DESCRIPTION\nWithout a command, \\fBvtouching\\fR is \\fBvtouching run\\fR: the desktop "
                        "preview (with no display, the offscreen demo). Every failure is one line on stderr and a "
                        "non\\-zero exit. This page is generated from the program's option table; docs/app.md "
                        "explains every mode.\n.SH COMMANDS\n");
  for (const CommandSpec& command : table.commands) {
    out += ".TP\n";
    for (std::string_view form : lines(command.forms)) out += str("\\fBvtouching ", command.name, "\\fR ", roff(form), "\n.br\n");
    out += roff(command.summary) + ".\n";
    std::string names;
    for (const OptionSpec* o : optionsOf(table, command.name)) {
      if (o->commands != "global") names += str(names.empty() ? "" : ", ", "\\-\\-", roff(o->name));
    }
    if (!names.empty()) out += "Options: " + names + ".\n";
  }
  out += ".SH OPTIONS\n";
  for (const SectionSpec& section : table.sections) {
    out += str(".SS ", roff(section.title), "\n");
    for (const OptionSpec& option : table.options) {
      if (option.section != section.key) continue;
      out += str(".TP\n\\fB\\-\\-", roff(option.name), "\\fR", option.value.empty() ? "" : " \\fI" + roff(option.value) + "\\fR",
                 "\n", roff(option.help), roff(defaultNote(option)), " [", roff(commaList(option.commands)), "]\n");
    }
  }
  out += ".SH ENVIRONMENT\n.TP\n.B VT_LOG\nlog level (debug, info, warn, error, off).\n.TP\n.B XR_RUNTIME_JSON\n"
         "the OpenXR runtime manifest (the installed headless runtime: share/vtouching/xrsim/xrsim.json).\n"
         ".SH SEE ALSO\ndocs/app.md, docs/outputs.md, docs/protocol.md (installed in share/doc/vtouching).\n";
  return out;
}

std::string markdownTable(const OptionTable& table, std::string_view section) {
  std::string out = "| option | commands | default | meaning |\n|---|---|---|---|\n";
  for (const OptionSpec& option : table.options) {
    if (option.section != section) continue;
    out += str("| ", markdownCode(optionSynopsis(option)), " | ", commaList(option.commands), " | ",
               option.fallback.empty() ? "" : markdownCode(option.fallback), " | ", option.help,
               option.repeatable ? " (repeatable)" : "", " |\n");
  }
  return out;
}

std::string bashCompletion(const OptionTable& table) {
  // What a value completes to, and for which "command --option" pairs.
  std::map<std::string, std::vector<std::string>> valueActions;
  std::string commandNames, perCommand;
  for (const CommandSpec& command : table.commands) {
    commandNames += str(commandNames.empty() ? "" : " ", command.name);
    std::string names;
    for (const OptionSpec* option : optionsOf(table, command.name)) {
      names += str(names.empty() ? "" : " ", "--", option->name);
      if (option->kind == ValueKind::Flag) continue;
      std::string action = "COMPREPLY=()";
      if (const auto choices = literalChoices(*option); !choices.empty()) {
        std::string list;
        for (const auto& c : choices) list += str(list.empty() ? "" : " ", c);
        action = str("COMPREPLY=($(compgen -W \"", list, "\" -- \"$cur\"))");
      } else if (option->kind == ValueKind::Path) {
        action = option->value.find("DIR") != std::string_view::npos ? "COMPREPLY=($(compgen -d -- \"$cur\"))"
                                                                      : "COMPREPLY=($(compgen -f -- \"$cur\"))";
      }
      valueActions[action].push_back(str("\"", command.name, " --", option->name, "\""));
    }
    perCommand += str("    ", command.name, ") options=\"", names, "\" ;;\n");
  }
  std::string valueCases;
  for (const auto& [action, patterns] : valueActions) {
    std::string joined;
    for (const auto& p : patterns) joined += str(joined.empty() ? "" : "|", p);
    valueCases += str("    ", joined, ")\n      ", action, "; return ;;\n");
  }
  return str("# bash completion for vtouching, generated from its option table (vtouching completion bash)\n"
             "_vtouching() {\n"
             "  local cur=${COMP_WORDS[COMP_CWORD]} prev=${COMP_WORDS[COMP_CWORD-1]} command=run options\n"
             "  if ((COMP_CWORD == 1)) && [[ $cur != -* ]]; then\n"
             "    COMPREPLY=($(compgen -W \"", commandNames, "\" -- \"$cur\")); return\n"
             "  fi\n"
             "  [[ ${COMP_WORDS[1]} != -* ]] && command=${COMP_WORDS[1]}\n"
             "  case \"$command $prev\" in\n", valueCases, "  esac\n"
             "  case $command in\n", perCommand, "    *) return ;;\n  esac\n"
             "  if [[ $cur == -* ]]; then\n"
             "    COMPREPLY=($(compgen -W \"$options\" -- \"$cur\"))\n"
             "  elif [[ $command == help ]]; then\n"
             "    COMPREPLY=($(compgen -W \"", commandNames, "\" -- \"$cur\"))\n"
             "  elif [[ $command == completion ]]; then\n"
             "    COMPREPLY=($(compgen -W \"bash\" -- \"$cur\"))\n"
             "  else\n"
             "    COMPREPLY=($(compgen -f -- \"$cur\"))\n"
             "  fi\n"
             "}\n"
             "complete -o filenames -F _vtouching vtouching\n");
}

}  // namespace vt::cli
