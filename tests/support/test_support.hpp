#pragma once
// Helpers shared by every test executable.
#include <chrono>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <optional>
#include <sstream>
#include <string>
#include <thread>

namespace vt::test {

/// The exit code by which a test process says "skipped": ctest's SKIP_RETURN_CODE for every
/// Catch test (cmake/VtTarget.cmake) and the shell-script tests.
inline constexpr int kSkipExitCode = VT_TEST_SKIP_CODE;

/// A millisecond in nanoseconds (the clocks' unit).
inline constexpr std::int64_t kMs = 1'000'000;

/// Records that the running test case skips (VT_SKIP) and why.
void noteSkipped(const std::string& reason);

/// The process exit code for Catch's result: 1 when anything failed, else kSkipExitCode when a
/// test case skipped (so ctest counts it as skipped, not passed), else 0.
int exitCode(int catchResult);

/// The published Pixel2Taxel dataset, or nullopt when it is not next to the project.
std::optional<std::filesystem::path> datasetDir();

/// The project source tree (for committed goldens and fixtures).
std::filesystem::path sourceDir();

/// A fresh, writable folder under the build tree for one test's outputs.
std::filesystem::path outputDir(const std::string& testName);

/// Runs `provoke` (which breaks a VT_INVARIANT) in a child process: checked builds
/// (VT_CHECKED_INVARIANTS: debug, sanitizers) must abort through assertFailed, release
/// builds must count the violation and go on. True when the build behaved as its kind must.
bool invariantHandled(const std::function<void()>& provoke);

/// Polls `done` every millisecond for up to `limit_ms` (for state another thread changes);
/// true as soon as it holds.
template <class F>
bool eventually(F done, int limit_ms = 3000) {
  for (int i = 0; i < limit_ms; ++i) {
    if (done()) return true;
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  return done();
}

}  // namespace vt::test

/// Skips the rest of a test case (Catch2 v2 has no SKIP): a warning now, and the test process
/// exits with kSkipExitCode unless something failed, so ctest lists the test as skipped.
/// Use it in the TEST_CASE body itself (it returns from the enclosing function).
#define VT_SKIP(reason)                                  \
  do {                                                   \
    std::ostringstream vtSkipReason;                     \
    vtSkipReason << reason;                              \
    ::vt::test::noteSkipped(vtSkipReason.str());         \
    WARN("skipped: " << vtSkipReason.str());             \
    return;                                              \
  } while (false)
