// vtouching: spatially aligned visual-tactile perception in VR. Dispatches subcommands;
// every failure becomes one line on stderr and a non-zero exit.
#include <cstdio>
#include <exception>
#include <filesystem>
#include <new>
#include <stdexcept>
#include <string>
#include <vector>

#include "cli.hpp"
#include "vt/core/error.hpp"
#include "vt/core/log.hpp"
#include "vt/core/stop.hpp"

namespace {

// The one-line promise holds even for messages from libraries that end in or contain newlines.
int printError(const char* kind, std::string message) {
  while (!message.empty() && (message.back() == '\n' || message.back() == '\r' || message.back() == ' ')) message.pop_back();
  for (char& c : message) {
    if (c == '\n' || c == '\r') c = ' ';
  }
  std::fprintf(stderr, "vtouching: %s: %s\n", kind, message.c_str());
  return 1;
}

bool wantsHelp(const std::vector<std::string>& words) {
  for (std::size_t i = 1; i < words.size(); ++i) {
    if (words[i] == "--help" || words[i] == "-h") return true;
  }
  return false;
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<std::string> words(argv + 1, argv + argc);
  try {
    // One shutdown path: Ctrl-C and SIGTERM set the process stop request that every loop
    // watches and that silences every actuator output; each command then ends cleanly.
    vt::installStopSignals();
    // Global options may appear anywhere.
    for (std::size_t i = 0; i < words.size(); ++i) {
      const bool joined = words[i].rfind("--log=", 0) == 0;
      if (words[i] != "--log" && !joined) continue;
      if (!joined && i + 1 >= words.size()) vt::fail("--log needs a value (debug|info|warn|error|off)");
      vt::log::Level level{};
      if (!vt::log::parseLevel(joined ? words[i].substr(6) : words[i + 1], level)) vt::fail("--log expects debug|info|warn|error|off");
      vt::log::setLevel(level);
      words.erase(words.begin() + long(i), words.begin() + long(i) + (joined ? 1 : 2));
      break;
    }
    if (!words.empty() && (words[0] == "--version" || words[0] == "version")) {
      std::printf("vtouching %s\n", VT_VERSION);
      return 0;
    }
    if (words.empty()) words = {"run"};  // the default command: the desktop preview
    if (words[0] == "--help" || words[0] == "-h") words = {"help"};
    // Options without a command belong to the default command: `vtouching --xr` = `vtouching run --xr`.
    if (words[0].rfind("--", 0) == 0) words.insert(words.begin(), "run");
    if (!vt::cli::findCommand(words[0])) {
      std::fprintf(stderr, "vtouching: unknown command '%s' (try 'vtouching help')\n", words[0].c_str());
      return 2;
    }
    if (wantsHelp(words)) words = {"help", words[0]};  // `vtouching CMD --help` = `vtouching help CMD`
    const vt::cli::Command* command = vt::cli::findCommand(words[0]);
    vt::cli::Args args(words[0], std::vector<std::string>(words.begin() + 1, words.end()));
    return command->run(args);
  } catch (const vt::Error& e) {
    return printError("error", e.what());
  } catch (const std::filesystem::filesystem_error& e) {
    // Names the path and the reason (a symlink loop, permission denied, ...) instead of the library's text.
    return printError("error", "'" + e.path1().string() + "': " + e.code().message());
  } catch (const std::bad_alloc&) {
    // Within every budget, yet more than this machine (or its memory limit) holds: say what was loading.
    const std::string loading = vt::failedLoad();
    return printError("error", "out of memory" + (loading.empty() ? std::string() : " while loading " + loading) +
                                   " (within the size budgets of docs/RELIABILITY.md, but more than this process may use)");
  } catch (const std::length_error& e) {
    const std::string loading = vt::failedLoad();
    return printError("error", std::string("a size from the input is too large (") + e.what() + ")" +
                                   (loading.empty() ? "" : " in " + loading));
  } catch (const std::exception& e) {
    return printError("unexpected error", e.what());
  }
}
