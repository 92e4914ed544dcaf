// Headset mode on xrsim without any script (the head looks straight ahead): the table is placed
// in front of the head, so the mirror frame that app.cli.headset_mirror_default_head_under_xvfb
// saved (VT_MIRROR_DEFAULT_PNG) shows it in its lower centre. Skips when run on its own.
#include <cstdlib>

#include <catch2/catch.hpp>

#include "test_support.hpp"
#include "vt/scene/image.hpp"

using namespace vt;

TEST_CASE("headset mirror without a script shows the table in its lower centre", "[mirror_placement]") {
  const char* path = std::getenv("VT_MIRROR_DEFAULT_PNG");
  if (!path) VT_SKIP("VT_MIRROR_DEFAULT_PNG unset (ctest sets it after running the headset mode under xvfb-run)");
  const Image8 image = loadImage8(path, 4);
  REQUIRE(image.width == 320);
  REQUIRE(image.height == 180);
  // Wood (the assets' table: red over green over blue) in the middle third, bottom 40 %; the
  // sky above it is not.
  auto woodShare = [&](int y0, int y1) {
    std::size_t wood = 0, all = 0;
    for (int y = y0; y < y1; ++y) {
      for (int x = image.width / 3; x < image.width * 2 / 3; ++x, ++all) {
        const int r = image.at(x, y, 0), g = image.at(x, y, 1), b = image.at(x, y, 2);
        if (r > g && g > b && r - b > 40) ++wood;
      }
    }
    return double(wood) / double(all);
  };
  const double lower = woodShare(image.height * 6 / 10, image.height);
  const double upper = woodShare(0, image.height * 3 / 10);
  INFO("wood share: lower centre " << lower << ", upper centre " << upper);
  CHECK(lower > 0.2);
  CHECK(upper < 0.05);
}
