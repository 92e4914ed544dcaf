// The option table against code and docs: the checks catch a command that reads an option the
// table does not give it, an option the table gives but no code reads, a default that differs,
// docs that cite an option a command does not take; docs/app.md's tables are the table's.
#include <catch2/catch.hpp>

#include <fstream>
#include <regex>
#include <sstream>

#include "cli.hpp"
#include "cli/help_text.hpp"
#include "cli/option_checks.hpp"
#include "test_support.hpp"

using namespace vt::cli;
using Catch::Matchers::Contains;

namespace {

constexpr SectionSpec kSections[] = {{"main", "Main"}};
constexpr CommandSpec kCommands[] = {{"paint", "paints", "FILE [options]", "canvas.png"}};
constexpr OptionSpec kOptions[] = {
    {"colour", "red|green", ValueKind::Choice, "red", "paint", "main", "the colour"},
    {"width", "N", ValueKind::Integer, "2", "paint", "main", "brush width"},
    {"dry", "", ValueKind::Flag, "", "paint", "main", "no paint"},
};
constexpr OptionTable kTable{kSections, kCommands, kOptions};

int paintReadsAll(Args& args) {
  args.valueOr("colour", "red");
  args.intOr("width", 2);
  args.flag("dry");
  args.positionals();
  args.finish();
  return 0;
}
int paintForgetsDry(Args& args) {
  args.valueOr("colour", "red");
  args.intOr("width", 2);
  args.finish();
  return 0;
}
int paintOtherDefault(Args& args) {
  args.intOr("width", 3);
  args.finish();
  return 0;
}
int paintUndeclared(Args& args) {
  args.flag("glossy");
  args.finish();
  return 0;
}

std::string readText(const std::filesystem::path& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

std::string joined(const std::vector<std::string>& lines) {
  std::string out;
  for (const auto& l : lines) out += l + "\n";
  return out;
}

}  // namespace

TEST_CASE("The option table check finds code and table that disagree", "[app][cli][table]") {
  const Command good[] = {{"paint", &paintReadsAll}};
  CHECK(checkOptionTable(kTable, good).empty());
  const Command forgets[] = {{"paint", &paintForgetsDry}};
  CHECK_THAT(joined(checkOptionTable(kTable, forgets)), Contains("paint takes --dry (the table) but its code never reads it"));
  const Command otherDefault[] = {{"paint", &paintOtherDefault}};
  CHECK_THAT(joined(checkOptionTable(kTable, otherDefault)), Contains("--width defaults to '2'"));
  const Command undeclared[] = {{"paint", &paintUndeclared}};
  CHECK_THAT(joined(checkOptionTable(kTable, undeclared)), Contains("reads --glossy, which no entry declares"));
  const Command extra[] = {{"paint", &paintReadsAll}, {"erase", &paintReadsAll}};
  CHECK_THAT(joined(checkOptionTable(kTable, extra)), Contains("VT_COMMAND(erase) is not in the option table"));
  CHECK_THAT(joined(checkOptionTable(kTable, {})), Contains("command 'paint' that no VT_COMMAND defines"));
}

TEST_CASE("The app's option table is consistent in itself", "[app][cli][table]") {
  // The commands live in the vtouching binary (`vtouching help --check` runs them); here the
  // table alone: sections, defaults that parse, no command taking a name twice.
  std::vector<std::string> problems;
  for (const std::string& p : checkOptionTable(optionTable(), {})) {
    if (p.find("no VT_COMMAND defines") == std::string::npos) problems.push_back(p);
  }
  CHECK(joined(problems).empty());
}

TEST_CASE("Each command's help shows each option with its help line and default", "[app][cli][table]") {
  const std::string run = commandHelp(optionTable(), *findCommandSpec(optionTable(), "run"));
  for (const char* option : {"--output", "--channels", "--pose-sampling", "--haptic-latency-ms", "--record-csv"})
    CHECK_THAT(run, Contains(option));
  CHECK_THAT(run, Contains("(default: predict)"));
  CHECK_THAT(run, Contains("usage: vtouching run [options]"));
  const std::string render = commandHelp(optionTable(), *findCommandSpec(optionTable(), "render"));
  CHECK_THAT(render, Contains("vtouching render --trajectory FILE --out DIR [options]"));
  CHECK_THAT(render, !Contains("--connect"));
  const std::string man = manPage(optionTable(), "0.0.0");
  CHECK_THAT(man, Contains(".SH OPTIONS"));
  CHECK_THAT(man, Contains("\\-\\-haptic\\-latency\\-ms"));
}

TEST_CASE("A cited command line is checked against the option table", "[app][cli][docs]") {
  const OptionTable& t = optionTable();
  CHECK(checkCitedCommand(t, "vtouching run --trajectory assets/trajectories/slide.csv") ==
        "vtouching run does not take --trajectory");
  CHECK(checkCitedCommand(t, "vtouching render --trajectory assets/trajectories/slide.csv --out out/slide --fps 10").empty());
  CHECK(checkCitedCommand(t, "build/app/vtouching render --out o --size 96ox540") == "vtouching render: --size expects WxH, got '96ox540'");
  CHECK(checkCitedCommand(t, "vtouching run --model fast") == "vtouching run: --model 'fast' is not paper|texture|taxel");
  CHECK(checkCitedCommand(t, "vtouching frobnicate") == "no command 'frobnicate'");
  CHECK(checkCitedCommand(t, "vtouching run --glove hid:1234 --output audio:plughw:0 --output osc://h:1?blocks").empty());
  // Synopses: brackets, alternatives and placeholders.
  CHECK(checkCitedCommand(t, "vtouching render --out DIR [--scene FILE.gltf | --dataset DIR | --builtin] [--size WxH]").empty());
  CHECK(checkCitedCommand(t, "XR_RUNTIME_JSON=x.json XRSIM_FRAMES=90 build/app/vtouching --xr # the headset").empty());
  CHECK(checkCitedCommand(t, "serve --video").empty());
  CHECK(checkCitedCommand(t, "vtouching stats --out") == "vtouching stats --out needs a value");
  CHECK(checkCitedCommand(t, "render --trajectory", false).empty());  // prose naming the mode
  CHECK(checkCitedCommand(t, "vtouching render --out o --builtin [--overlay|--stereo] --frames $n --log warn;").empty());
  const auto cited = citedCommands(t, "text `vtouching run\n--xr` and `render --fps` here\n```sh\nvtouching serve \\\n  --bind 0.0.0.0:1\n"
                                      "echo vtouching-demo\nsudo netns-session.sh --bin build/app/vtouching --seconds 5\n```\n`--hand skeleton` alone\n");
  REQUIRE(cited.size() == 3);
  CHECK(cited[0].line == 1);
  CHECK(cited[0].text == "vtouching run --xr");
  CHECK(cited[1].text == "render --fps");
  CHECK(cited[2].line == 4);
  CHECK(cited[2].text == "vtouching serve    --bind 0.0.0.0:1");
}

TEST_CASE("Every vtouching command line in README.md and docs/*.md is valid as written", "[app][cli][docs]") {
  std::vector<std::filesystem::path> files{vt::test::sourceDir() / "README.md"};
  for (const auto& entry : std::filesystem::directory_iterator(vt::test::sourceDir() / "docs")) {
    if (entry.path().extension() == ".md") files.push_back(entry.path());
  }
  std::string problems;
  int checked = 0;
  for (const auto& file : files) {
    for (const CitedCommand& c : citedCommands(optionTable(), readText(file))) {
      ++checked;
      if (const std::string why = checkCitedCommand(optionTable(), c.text, c.runnable); !why.empty())
        problems += std::filesystem::relative(file, vt::test::sourceDir()).string() + ":" + std::to_string(c.line) + ": " + why + "\n    " + c.text + "\n";
    }
  }
  INFO(checked << " command lines checked");
  CHECK(checked > 50);
  CHECK(problems == "");  // the expansion lists them
}

TEST_CASE("docs/app.md's option tables are generated from the option table", "[app][cli][docs]") {
  // Each table sits between "<!-- options: KEY -->" and "<!-- end options -->";
  // VT_UPDATE_GOLDENS=1 rewrites them from the table.
  const auto path = vt::test::sourceDir() / "docs" / "app.md";
  std::string text = readText(path);
  std::string updated;
  std::string stale;
  std::size_t at = 0;
  int tables = 0;
  const std::string open = "<!-- options: ", close = "<!-- end options -->";
  while (true) {
    const std::size_t start = text.find(open, at);
    if (start == std::string::npos) break;
    const std::size_t keyEnd = text.find(" -->\n", start);
    const std::size_t end = text.find(close, keyEnd);
    REQUIRE(keyEnd != std::string::npos);
    REQUIRE(end != std::string::npos);
    const std::string key = text.substr(start + open.size(), keyEnd - start - open.size());
    const std::string expected = markdownTable(optionTable(), key);
    if (text.substr(keyEnd + 5, end - keyEnd - 5) != expected) stale += " " + key;
    updated += text.substr(at, keyEnd + 5 - at) + expected;
    at = end;
    ++tables;
  }
  updated += text.substr(at);
  CHECK(tables == int(optionTable().sections.size()));
  if (!stale.empty() && std::getenv("VT_UPDATE_GOLDENS")) {
    std::ofstream(path) << updated;
    WARN("rewrote the option tables in docs/app.md:" << stale);
    return;
  }
  INFO("stale tables (VT_UPDATE_GOLDENS=1 rewrites them):" << stale);
  CHECK(stale.empty());
}
