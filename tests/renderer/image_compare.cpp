#include "image_compare.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstring>

#include <catch2/catch.hpp>

#include "test_support.hpp"
#include "vt/core/error.hpp"

namespace vt::test {

ImageDiff compareImages(const Image8& actual, const Image8& expected) {
  if (actual.width != expected.width || actual.height != expected.height || actual.channels != 4 ||
      expected.channels != 4) {
    fail("compareImages: ", actual.width, "x", actual.height, "x", actual.channels, " vs ", expected.width, "x",
         expected.height, "x", expected.channels);
  }
  ImageDiff d;
  double squared = 0.0;
  std::size_t bad = 0;
  for (int y = 0; y < actual.height; ++y) {
    for (int x = 0; x < actual.width; ++x) {
      int pixelMax = 0;
      for (int c = 0; c < 3; ++c) {
        const int e = std::abs(int(actual.at(x, y, c)) - int(expected.at(x, y, c)));
        squared += double(e) * e;
        pixelMax = std::max(pixelMax, e);
      }
      d.maxError = std::max(d.maxError, pixelMax);
      if (pixelMax > kBadPixelError) ++bad;
    }
  }
  const double pixels = double(actual.width) * actual.height;
  const double mse = squared / (pixels * 3.0);
  d.psnr_db = mse == 0.0 ? 99.0 : 10.0 * std::log10(255.0 * 255.0 / mse);
  d.badFraction = double(bad) / pixels;
  return d;
}

double luminance(const Image8& image, int x, int y) {
  return 0.2126 * image.at(x, y, 0) + 0.7152 * image.at(x, y, 1) + 0.0722 * image.at(x, y, 2);
}

bool withinTolerance(const ImageDiff& diff) {
  return diff.psnr_db >= kMinPsnr_db && diff.badFraction <= kMaxBadFraction;
}

Image8 diffImage(const Image8& actual, const Image8& expected) {
  Image8 out(actual.width, actual.height, 4);
  for (int y = 0; y < actual.height; ++y) {
    for (int x = 0; x < actual.width; ++x) {
      for (int c = 0; c < 3; ++c) {
        out.at(x, y, c) = std::uint8_t(std::min(255, 4 * std::abs(int(actual.at(x, y, c)) - int(expected.at(x, y, c)))));
      }
      out.at(x, y, 3) = 255;
    }
  }
  return out;
}

void checkGolden(const Image8& actual, const std::string& name) {
  const std::filesystem::path golden = sourceDir() / "tests" / "golden" / (name + ".png");
  const char* update = std::getenv("VT_UPDATE_GOLDENS");
  if (update && std::strcmp(update, "1") == 0) {
    savePng(golden, actual);
    WARN("updated golden " << golden.string());
    return;
  }
  INFO("golden " << golden.string());
  REQUIRE(std::filesystem::exists(golden));  // new image? run scripts/approve-goldens.sh
  const Image8 expected = loadImage8(golden, 4);
  REQUIRE(expected.width == actual.width);
  REQUIRE(expected.height == actual.height);
  const ImageDiff d = compareImages(actual, expected);
  WARN(name << ": PSNR " << d.psnr_db << " dB, max channel error " << d.maxError << ", pixels off by >"
            << kBadPixelError << ": " << 100.0 * d.badFraction << "%");
  if (!withinTolerance(d)) {
    const std::filesystem::path dir = outputDir(name);
    savePng(dir / "actual.png", actual);
    savePng(dir / "expected.png", expected);
    savePng(dir / "diff.png", diffImage(actual, expected));
    FAIL_CHECK("differs beyond tolerance (PSNR >= " << kMinPsnr_db << " dB, <= " << 100.0 * kMaxBadFraction
                                                    << "% bad pixels); actual and diff in " << dir.string());
  }
}

}  // namespace vt::test
