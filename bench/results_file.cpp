#include "results_file.hpp"

#include <sched.h>
#include <sys/utsname.h>

#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <fstream>
#include <sstream>
#include <thread>

#include "vt/core/error.hpp"

namespace vt::bench {
namespace {

// The value of the first "key : value" line of a /proc file, or "".
std::string procField(const char* file, const std::string& key) {
  std::ifstream in(file);
  for (std::string line; std::getline(in, line);) {
    const auto colon = line.find(':');
    if (colon == std::string::npos) continue;
    std::string name = line.substr(0, colon);
    name.erase(name.find_last_not_of(" \t") + 1);
    if (name != key) continue;
    const auto start = line.find_first_not_of(" \t", colon + 1);
    return start == std::string::npos ? "" : line.substr(start);
  }
  return "";
}

// stdout of a shell command, trailing newline removed; "" when it fails.
std::string commandOutput(const std::string& command) {
  std::string out;
  if (FILE* pipe = popen(command.c_str(), "r")) {
    char buffer[256];
    while (const std::size_t n = std::fread(buffer, 1, sizeof buffer, pipe)) out.append(buffer, n);
    if (pclose(pipe) != 0) return "";
  }
  while (!out.empty() && out.back() == '\n') out.pop_back();
  return out;
}

std::string shellQuoted(const std::string& text) {
  std::string quoted = "'";
  for (char c : text) quoted += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return quoted + "'";
}

nlohmann::ordered_json loadJson(const std::array<double, 3>& load) { return {load[0], load[1], load[2]}; }

}  // namespace

std::array<double, 3> loadAverage() {
  std::array<double, 3> load{-1, -1, -1};
  if (getloadavg(load.data(), 3) != 3) load = {-1, -1, -1};
  return load;
}

nlohmann::ordered_json machineInfo() {
  nlohmann::ordered_json machine;
  machine["cpu_model"] = procField("/proc/cpuinfo", "model name");
  std::vector<std::string> flags;
  std::istringstream words(procField("/proc/cpuinfo", "flags"));
  for (std::string flag; words >> flag;) flags.push_back(flag);
  machine["cpu_flags"] = flags;
  machine["logical_cores"] = std::thread::hardware_concurrency();
  cpu_set_t set;
  CPU_ZERO(&set);
  machine["cores_available"] = sched_getaffinity(0, sizeof set, &set) == 0 ? CPU_COUNT(&set) : -1;
  const std::string memory = procField("/proc/meminfo", "MemTotal");  // "24576000 kB"
  machine["memory_gib"] = memory.empty() ? -1.0 : std::strtod(memory.c_str(), nullptr) / (1024.0 * 1024.0);
  utsname name{};
  machine["kernel"] = uname(&name) == 0 ? std::string(name.sysname) + " " + name.release : "";
  return machine;
}

nlohmann::ordered_json sourceInfo(const std::filesystem::path& sourceDir) {
  const std::string git = "git -C " + shellQuoted(sourceDir.string()) + " ";
  const std::string commit = commandOutput(git + "rev-parse HEAD 2>/dev/null");
  nlohmann::ordered_json source;
  source["commit"] = commit.empty() ? "unknown" : commit;
  // Tracked files only: a fresh results file is untracked and says nothing about the code.
  source["dirty"] = !commit.empty() && !commandOutput(git + "status --porcelain --untracked-files=no 2>/dev/null").empty();
  return source;
}

nlohmann::json figuresFromOutput(const std::string& suite, const std::string& printed) {
  std::istringstream lines(printed);
  std::size_t offset = 0;
  for (std::string line; std::getline(lines, line); offset += line.size() + 1) {
    if (line.empty() || line[0] != '{') continue;
    std::istringstream rest(printed.substr(offset));
    nlohmann::json figures;
    try {
      rest >> figures;  // one value; what follows it is the suite's other output
    } catch (const nlohmann::json::exception&) {
      continue;
    }
    if (figures.is_object()) return figures;
  }
  fail("vt_bench ", suite, ": printed no JSON object of figures to store");
}

std::string utcNow() {
  const std::time_t now = std::time(nullptr);
  std::tm utc{};
  gmtime_r(&now, &utc);
  char text[32];
  std::strftime(text, sizeof text, "%Y-%m-%dT%H:%M:%SZ", &utc);
  return text;
}

nlohmann::ordered_json resultsDocument(const std::string& suite, const RunRecord& run, nlohmann::json figures,
                                       const std::filesystem::path& sourceDir) {
  std::string command = "vt_bench";  // the binary's own path depends on the build folder
  for (std::size_t i = 1; i < run.argv.size(); ++i) command += " " + run.argv[i];
  nlohmann::ordered_json doc;
  doc["suite"] = suite;
  doc["command"] = command;
  doc["exit_code"] = run.exitCode;
  doc["date"] = run.date;
  doc["wall_s"] = run.wall_s;
  doc["load_average"] = {{"before", loadJson(run.loadBefore)}, {"after", loadJson(run.loadAfter)}};
  doc["source"] = sourceInfo(sourceDir);
#ifdef __clang__
  constexpr const char* compiler = "clang " __clang_version__;
#else
  constexpr const char* compiler = "gcc " __VERSION__;
#endif
  doc["build"] = {{"type", VT_BUILD_TYPE}, {"compiler", compiler}};
  doc["machine"] = machineInfo();
  doc["figures"] = std::move(figures);
  return doc;
}

}  // namespace vt::bench
