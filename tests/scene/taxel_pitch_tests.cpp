// The scale of the published maps from their taxel pattern.
#include <catch2/catch.hpp>

#include <cstdio>
#include <filesystem>

#include "test_support.hpp"
#include "vt/scene/taxel_pitch.hpp"

using namespace vt;

TEST_CASE("A synthetic taxel grid gives back its scale") {
  // 0.35 mm/px: 1 mm taxels along x are 2.857 px, 2 mm lines along y are 5.714 px.
  ImageF map(400, 300, 1);
  for (int y = 0; y < map.height; ++y) {
    for (int x = 0; x < map.width; ++x) {
      const int line = int(double(y) * 0.35 / 2.0), taxel = int(double(x) * 0.35 / 1.0);
      map.at(x, y) = float((line * 7919 + taxel * 104729) % 97) / 96.0f;
    }
  }
  CHECK(estimateMmPerPixel(map) == Approx(0.35).epsilon(0.05));
  ImageF flat(200, 200, 1);
  CHECK(estimateMmPerPixel(flat) == 0.0);  // no pattern: no estimate
}

TEST_CASE("The published maps are about 0.35 mm per pixel by their taxel rows", "[dataset]") {
  const auto dir = test::datasetDir();
  if (!dir) VT_SKIP("published dataset not present");
  for (const auto& entry : std::filesystem::directory_iterator(*dir)) {
    if (!entry.is_directory()) continue;
    const std::string name = entry.path().filename().string();
    const double mm = estimateMmPerPixel(loadChannelAsFloat(entry.path() / (name + "_acc.png"), 0));
    std::printf("%s: %.3f mm/pixel\n", name.c_str(), mm);
    INFO(name);
    CHECK(mm > 0.25);
    CHECK(mm < 0.45);
  }
}
