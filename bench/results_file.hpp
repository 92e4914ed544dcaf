#pragma once
// Results files: one suite run stored as data (`vt_bench SUITE --out results/NAME.json`), the
// suite's own JSON figures wrapped with where and how they were measured, so docs tables are
// generated from, and checked against, stored runs (scripts/perf-docs.py).
#include <array>
#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace vt::bench {

/// The 1, 5 and 15 minute load averages now (-1 each where unknown).
std::array<double, 3> loadAverage();

/// The machine a figure was measured on: CPU model and flags, cores, memory, kernel.
nlohmann::ordered_json machineInfo();

/// The source tree's commit and whether tracked files differ from it (git, at run time).
nlohmann::ordered_json sourceInfo(const std::filesystem::path& sourceDir);

/// The suite's figures in what it printed with --json: the first line starting with '{' that
/// begins a JSON object (child processes may print before it, the suite after it). Throws
/// vt::Error naming the suite when there is none.
nlohmann::json figuresFromOutput(const std::string& suite, const std::string& printed);

/// What a suite run was: its command line, exit code, start date (UTC, ISO 8601), wall time and
/// the load averages before and after it.
struct RunRecord {
  std::vector<std::string> argv;
  int exitCode = 0;
  std::string date;
  double wall_s = 0;
  std::array<double, 3> loadBefore{}, loadAfter{};
};

/// The results document: suite, command, run record, source, build, machine, then `figures`.
nlohmann::ordered_json resultsDocument(const std::string& suite, const RunRecord& run, nlohmann::json figures,
                                       const std::filesystem::path& sourceDir);

/// The current UTC time as 2026-01-31T12:00:00Z.
std::string utcNow();

}  // namespace vt::bench
