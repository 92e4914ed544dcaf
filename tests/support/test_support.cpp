#include "test_support.hpp"

namespace vt::test {

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

}  // namespace vt::test
