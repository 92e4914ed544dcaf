#pragma once
// Child processes for the live paths: the program run to its end with a time limit, a server
// in the background, and xvfb-run for the ones that need a window.
#include <filesystem>
#include <string>
#include <vector>

#include <sys/types.h>

namespace vt::live {

/// Whether xvfb-run is on the PATH.
bool haveXvfb();
/// `args` run under `xvfb-run -a` (a private X server, lavapipe renders the window).
std::vector<std::string> withXvfb(std::vector<std::string> args);

/// Runs `args` (environment `env` added, "NAME=VALUE") with stdout and stderr into the two files,
/// and waits at most `timeout_s`. Throws vt::Error naming the program, its exit and its stderr
/// file when it fails or runs out of time (then it is killed with its children).
void runToEnd(const std::vector<std::string>& args, const std::vector<std::string>& env, const std::filesystem::path& out,
              const std::filesystem::path& err, double timeout_s);

/// A program running beside the measured one (the tactile server); killed if still running at destruction.
class Background {
 public:
  Background(const std::vector<std::string>& args, std::filesystem::path out, std::filesystem::path err);
  ~Background();
  Background(const Background&) = delete;
  Background& operator=(const Background&) = delete;
  /// Waits for a stdout line starting with `prefix` and returns what follows `marker` in it up to
  /// the next space (throws vt::Error when it exits or `timeout_s` passes first).
  std::string waitForLine(const std::string& prefix, const std::string& marker, double timeout_s);
  /// SIGINT, then waits up to `timeout_s` (throws vt::Error when it does not end cleanly).
  void stop(double timeout_s);

 private:
  pid_t m_pid = -1;
  std::filesystem::path m_out, m_err;
};

}  // namespace vt::live
