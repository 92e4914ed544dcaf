#pragma once
// Helpers shared by every test executable.
#include <filesystem>
#include <optional>
#include <string>

namespace vt::test {

/// The published Pixel2Taxel dataset, or nullopt when it is not next to the project.
std::optional<std::filesystem::path> datasetDir();

/// The project source tree (for committed goldens and fixtures).
std::filesystem::path sourceDir();

/// A fresh, writable folder under the build tree for one test's outputs.
std::filesystem::path outputDir(const std::string& testName);

}  // namespace vt::test

/// Skips the rest of a test case (Catch2 v2 has no SKIP) with a visible note.
#define VT_SKIP(reason)          \
  do {                           \
    WARN("skipped: " << reason); \
    return;                      \
  } while (false)
