#include <catch2/catch.hpp>

#include <cmath>
#include <cstdlib>

#include "vt/core/error.hpp"
#include "vt/scene/jpeg.hpp"

using Catch::Matchers::Contains;

namespace {

// A smooth gradient with a disc: JPEG keeps it within a few levels.
vt::Image8 testPattern(int w, int h, int channels) {
  vt::Image8 image(w, h, channels);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const bool disc = std::hypot(x - w / 2.0, y - h / 2.0) < w / 4.0;
      const std::uint8_t rgb[3] = {std::uint8_t(255 * x / w), std::uint8_t(255 * y / h), std::uint8_t(disc ? 220 : 40)};
      for (int c = 0; c < channels; ++c) image.at(x, y, c) = c < 3 ? rgb[c] : 255;
    }
  return image;
}

double meanAbsError(const vt::Image8& rgba, const vt::Image8& original) {
  double sum = 0;
  int n = 0;
  for (int y = 0; y < original.height; ++y)
    for (int x = 0; x < original.width; ++x)
      for (int c = 0; c < std::min(3, original.channels); ++c, ++n) sum += std::abs(rgba.at(x, y, c) - original.at(x, y, c));
  return sum / n;
}

}  // namespace

TEST_CASE("JPEG round trip of RGBA and RGB frames stays close to the original") {
  for (int channels : {3, 4}) {
    const vt::Image8 image = testPattern(480, 480, channels);
    const auto jpeg = vt::encodeJpeg(image, 80);
    CHECK(jpeg.size() > 1000);
    CHECK(jpeg.size() < image.pixels.size() / 10);
    const vt::Image8 back = vt::decodeJpeg(jpeg, "frame");
    REQUIRE(back.width == 480);
    REQUIRE(back.height == 480);
    REQUIRE(back.channels == 4);
    CHECK(meanAbsError(back, image) < 3.0);
    CHECK(back.at(10, 10, 3) == 255);
  }
}

TEST_CASE("Lower JPEG quality gives fewer bytes") {
  const vt::Image8 image = testPattern(256, 128, 3);
  CHECK(vt::encodeJpeg(image, 30).size() < vt::encodeJpeg(image, 95).size());
}

TEST_CASE("encodeJpeg refuses an empty image and a bad quality") {
  CHECK_THROWS_AS(vt::encodeJpeg(vt::Image8{}, 80), vt::Error);
  CHECK_THROWS_WITH(vt::encodeJpeg(testPattern(8, 8, 3), 0), Contains("quality"));
}

TEST_CASE("decodeJpeg names the source of corrupt or foreign data") {
  const auto jpeg = vt::encodeJpeg(testPattern(64, 64, 3), 80);
  const std::vector<std::uint8_t> png = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1A, '\n', 0, 0, 0, 0};
  CHECK_THROWS_WITH(vt::decodeJpeg(png, "video frame 7"), Contains("video frame 7") && Contains("not a JPEG"));
  CHECK_THROWS_WITH(vt::decodeJpeg(std::span(jpeg.data(), 20), "video frame 8"), Contains("video frame 8"));
  // Cut mid-scan: libjpeg would pad it grey with a warning; a frame like that is refused.
  CHECK_THROWS_WITH(vt::decodeJpeg(std::span(jpeg.data(), jpeg.size() / 2), "video frame 10"),
                    Contains("video frame 10") && Contains("cannot decode"));
  std::vector<std::uint8_t> garbage(jpeg.begin(), jpeg.begin() + 4);
  garbage.resize(3000, 0x5A);
  CHECK_THROWS_WITH(vt::decodeJpeg(garbage, "video frame 9"), Contains("video frame 9"));
}

TEST_CASE("decodeJpeg refuses data and images over its limits") {
  std::vector<std::uint8_t> huge(vt::kMaxJpegBytes + 1, 0);
  huge[0] = 0xFF, huge[1] = 0xD8, huge[2] = 0xFF;
  CHECK_THROWS_WITH(vt::decodeJpeg(huge, "big"), Contains("big") && Contains("limit"));
  // A header claiming 8192x8192: the start-of-frame height and width fields are patched.
  auto jpeg = vt::encodeJpeg(testPattern(16, 16, 3), 80);
  for (std::size_t i = 2; i + 8 < jpeg.size(); ++i) {
    if (jpeg[i] == 0xFF && jpeg[i + 1] == 0xC0) {
      jpeg[i + 5] = 0x20, jpeg[i + 6] = 0x00, jpeg[i + 7] = 0x20, jpeg[i + 8] = 0x00;
      break;
    }
  }
  CHECK_THROWS_WITH(vt::decodeJpeg(jpeg, "claimed"), Contains("claimed") && Contains("8192x8192"));
}
