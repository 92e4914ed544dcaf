#include <catch2/catch.hpp>

#include <fstream>

#include "test_support.hpp"
#include "vt/core/error.hpp"
#include "vt/scene/image.hpp"

using Catch::Matchers::Contains;

TEST_CASE("8-bit PNG round trip keeps every pixel") {
  const auto dir = vt::test::outputDir("png8");
  vt::Image8 image(5, 3, 4);
  for (std::size_t i = 0; i < image.pixels.size(); ++i) image.pixels[i] = std::uint8_t(i * 7);
  vt::savePng(dir / "a.png", image);
  const vt::Image8 back = vt::loadImage8(dir / "a.png", 4);
  CHECK(back.width == 5);
  CHECK(back.height == 3);
  CHECK(back.pixels == image.pixels);
}

TEST_CASE("16-bit PNG round trip keeps full precision, and reads as float") {
  const auto dir = vt::test::outputDir("png16");
  for (int channels : {1, 3}) {
    vt::Image16 image(7, 4, channels);
    for (std::size_t i = 0; i < image.pixels.size(); ++i) image.pixels[i] = std::uint16_t(i * 2311 + 1);
    vt::savePng16(dir / "a.png", image);
    const vt::Image16 back = vt::loadImage16(dir / "a.png", channels);
    CHECK(back.pixels == image.pixels);
    const vt::ImageF red = vt::loadChannelAsFloat(dir / "a.png", 0);
    CHECK(red.at(2, 1) == Approx(image.at(2, 1, 0) / 65535.0).margin(1e-6));
  }
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
