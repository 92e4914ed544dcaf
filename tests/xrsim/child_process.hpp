#pragma once
// Runs a program with its stdin held open by the test (hello_xr quits when stdin closes) and
// its output captured to a file, with a timeout.
#include <filesystem>
#include <map>
#include <string>
#include <vector>

namespace vt::test {

struct ChildResult {
  int exitCode = -1;     // -1 when killed by a signal or the timeout
  bool timedOut = false;
  std::string output;    // stdout + stderr
};

/// Runs argv[0] (absolute path) with extra environment variables; kills it after timeout_s.
ChildResult runChild(const std::vector<std::string>& argv, const std::map<std::string, std::string>& env,
                     const std::filesystem::path& logFile, double timeout_s);

}  // namespace vt::test
