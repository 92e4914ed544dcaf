// The headset mode's desktop mirror: the last mirror frame that app.cli.headset_mirror_under_xvfb
// saved (VT_MIRROR_PNG) shows the scene, not just the background. Skips when run on its own.
#include <cstdint>
#include <cstdlib>

#include <catch2/catch.hpp>

#include "test_support.hpp"
#include "vt/scene/image.hpp"

using namespace vt;

TEST_CASE("headset mirror frame shows the scene", "[mirror]") {
  const char* path = std::getenv("VT_MIRROR_PNG");
  if (!path) VT_SKIP("VT_MIRROR_PNG unset (ctest sets it after running the headset mode under xvfb-run)");
  const Image8 image = loadImage8(path, 4);
  REQUIRE(image.width == 320);
  REQUIRE(image.height == 180);
  // The top-left corner is sky (the clear colour); the table and plates differ clearly from it.
  const std::uint8_t* corner = image.pixels.data();
  std::size_t differing = 0;
  for (std::size_t i = 0; i < image.pixels.size(); i += 4) {
    int diff = 0;
    for (int c = 0; c < 3; ++c) diff += std::abs(int(image.pixels[i + c]) - int(corner[c]));
    if (diff > 60) ++differing;
  }
  const double fraction = double(differing) / double(image.pixels.size() / 4);
  INFO("non-background fraction " << fraction);
  CHECK(fraction > 0.05);
  CHECK(fraction < 0.9);
}
