#include <catch2/catch.hpp>

#include <fstream>

#include "test_support.hpp"
#include "vt/core/error.hpp"
#include "vt/scene/image.hpp"

using Catch::Matchers::Contains;

TEST_CASE("8-bit PNG round trip keeps every pixel, for every channel count") {
  const auto dir = vt::test::outputDir("png8");
  for (int channels = 1; channels <= 4; ++channels) {
    // Pseudo-random bytes with some smooth rows: every Paeth prediction branch and wrap-around occurs.
    vt::Image8 image(37, 23, channels);
    std::uint32_t state = 12345u + std::uint32_t(channels);
    for (std::size_t i = 0; i < image.pixels.size(); ++i) {
      state = state * 1664525u + 1013904223u;
      image.pixels[i] = (i / (37u * channels)) % 3 == 0 ? std::uint8_t(i) : std::uint8_t(state >> 24);
    }
    vt::savePng(dir / "a.png", image);
    const vt::Image8 back = vt::loadImage8(dir / "a.png", channels);
    CHECK(back.width == 37);
    CHECK(back.height == 23);
    CHECK(back.pixels == image.pixels);
    const std::vector<std::uint8_t> bytes = vt::encodePng(image);
    CHECK_FALSE(vt::is16BitImage(bytes));
    CHECK(vt::loadImage8(bytes, "encoded", channels).pixels == image.pixels);
  }
}

TEST_CASE("16-bit PNG round trip keeps full precision for every channel count, and reads as float") {
  const auto dir = vt::test::outputDir("png16");
  for (int channels = 1; channels <= 4; ++channels) {
    vt::Image16 image(29, 17, channels);
    std::uint32_t state = 777u + std::uint32_t(channels);
    for (std::size_t i = 0; i < image.pixels.size(); ++i) {
      state = state * 1664525u + 1013904223u;
      image.pixels[i] = i % 5 == 0 ? std::uint16_t(i * 2311 + 1) : std::uint16_t(state >> 16);
    }
    vt::savePng16(dir / "a.png", image);
    const vt::Image16 back = vt::loadImage16(dir / "a.png", channels);
    CHECK(back.width == 29);
    CHECK(back.height == 17);
    CHECK(back.pixels == image.pixels);
    const vt::ImageF red = vt::loadChannelAsFloat(dir / "a.png", 0);
    CHECK(red.at(2, 1) == Approx(image.at(2, 1, 0) / 65535.0).margin(1e-6));
    const std::vector<std::uint8_t> bytes = vt::encodePng16(image);
    CHECK(vt::is16BitImage(bytes));
    CHECK(vt::loadImage16(bytes, "encoded", channels).pixels == image.pixels);
  }
}

TEST_CASE("Encoding an empty image or 5 channels fails naming the file") {
  const auto dir = vt::test::outputDir("png_bad");
  REQUIRE_THROWS_WITH(vt::savePng(dir / "empty.png", vt::Image8(0, 4, 3)), Contains("empty.png") && Contains("empty image"));
  REQUIRE_THROWS_WITH(vt::savePng16(dir / "five.png", vt::Image16(2, 2, 5)), Contains("five.png") && Contains("5 channels"));
}

TEST_CASE("A missing image names the file") {
  REQUIRE_THROWS_WITH(vt::loadImage8("/nonexistent/tex.png"), Contains("/nonexistent/tex.png") && Contains("not found"));
}

TEST_CASE("A corrupt PNG names the file and says it cannot be decoded") {
  const auto dir = vt::test::outputDir("corrupt");
  std::ofstream(dir / "bad.png", std::ios::binary) << "\x89PNG\r\n\x1a\n this is not a png";
  REQUIRE_THROWS_WITH(vt::loadImage8(dir / "bad.png"), Contains("bad.png") && Contains("cannot decode"));
  REQUIRE_THROWS_AS(vt::loadImage16(dir / "bad.png", 1), vt::Error);
}
