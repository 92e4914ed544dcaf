#pragma once
// Golden-image comparison for renderer tests: metrics, tolerance, and failure artefacts.
#include <string>

#include "vt/scene/image.hpp"

namespace vt::test {

/// How far an image is from its reference.
struct ImageDiff {
  double psnr_db = 0.0;       // over RGB; +inf for identical images (reported as 99)
  int maxError = 0;           // largest per-channel absolute difference (0..255)
  double badFraction = 0.0;   // pixels with any channel off by more than kBadPixelError
};

inline constexpr int kBadPixelError = 24;
/// Lavapipe is deterministic on one machine; the slack covers other CPUs / LLVM versions.
inline constexpr double kMinPsnr_db = 35.0;
inline constexpr double kMaxBadFraction = 0.005;

/// Compares two RGBA8 images of the same size (throws vt::Error when sizes differ).
ImageDiff compareImages(const Image8& actual, const Image8& expected);
bool withinTolerance(const ImageDiff& diff);
/// Rec. 709 luminance of pixel (x, y), 0..255.
double luminance(const Image8& image, int x, int y);
/// |actual - expected| per channel, scaled x4 so small differences show, opaque.
Image8 diffImage(const Image8& actual, const Image8& expected);

/// Compares `actual` with tests/golden/<name>.png, reporting PSNR and max error; on failure
/// writes actual, expected and diff images under the build's test-output/<name>/.
/// With VT_UPDATE_GOLDENS=1 it rewrites the golden instead (scripts/approve-goldens.sh).
void checkGolden(const Image8& actual, const std::string& name);

}  // namespace vt::test
