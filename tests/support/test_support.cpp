#include "test_support.hpp"

#include <sys/wait.h>
#include <unistd.h>

#include <csignal>
#include <cstdio>
#include <set>

#include "vt/core/error.hpp"

namespace vt::test {

namespace {
std::set<std::string>& skipReasons() {
  static std::set<std::string> reasons;  // a set: a skipping case re-entered per SECTION counts once
  return reasons;
}
}  // namespace

void noteSkipped(const std::string& reason) { skipReasons().insert(reason); }

int exitCode(int catchResult) {
  // Catch returns the failed-assertion count (or the listed-test count with --list-*); any of
  // it must never read as the skip code.
  if (catchResult != 0) return 1;
  if (skipReasons().empty()) return 0;
  for (const auto& reason : skipReasons()) std::printf("SKIPPED: %s\n", reason.c_str());
  return kSkipExitCode;
}

std::optional<std::filesystem::path> datasetDir() {
  std::filesystem::path dir = VT_DATASET_DIR;
  if (std::filesystem::is_directory(dir / "pattern_board")) return dir;
  return std::nullopt;
}

std::filesystem::path sourceDir() { return VT_SOURCE_DIR; }

std::filesystem::path outputDir(const std::string& testName) {
  std::filesystem::path dir = std::filesystem::path(VT_TEST_OUTPUT_DIR) / testName;
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

bool invariantHandled(const std::function<void()>& provoke) {
  const pid_t child = fork();
  if (child == 0) {
    // The test runner's SIGABRT report is no business of the child: it must die of the abort.
    std::signal(SIGABRT, SIG_DFL);
    const std::uint64_t before = invariantViolations();
    provoke();
    _exit(invariantViolations() > before ? 0 : 3);
  }
  int status = 0;
  if (child < 0 || waitpid(child, &status, 0) != child) return false;
#ifdef VT_CHECKED_INVARIANTS
  return WIFSIGNALED(status) && WTERMSIG(status) == SIGABRT;
#else
  return WIFEXITED(status) && WEXITSTATUS(status) == 0;
#endif
}

}  // namespace vt::test
