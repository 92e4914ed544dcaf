#pragma once
// Small synthetic scans written under the build tree, shared by the acquisition tests.
#include <filesystem>
#include <string>

#include "test_support.hpp"
#include "vt/acquisition/synthetic.hpp"

namespace vt::acq::test {

/// A 20 x 12 mm scan (6 lines x 8 passes): quick to simulate and process.
inline SyntheticOptions smallOptions(SyntheticKind kind = SyntheticKind::ReliefCeramicTile) {
  SyntheticOptions o;
  o.kind = kind;
  o.scanLength_m = 0.02;
  o.lines = 6;
  o.photoWidth = 320;
  o.photoHeight = 240;
  o.topViewScale_px_per_mm = 4.0;
  o.seed = 7;
  return o;
}

/// A simulated scan in a fresh folder named after the test.
struct ScanOnDisk {
  SyntheticTruth truth;
  std::filesystem::path dir;
};

inline ScanOnDisk writeScan(const std::string& testName, const SyntheticOptions& options) {
  const auto dir = vt::test::outputDir(testName);
  return {writeSyntheticScan(options, dir, 2), dir};
}

}  // namespace vt::acq::test
