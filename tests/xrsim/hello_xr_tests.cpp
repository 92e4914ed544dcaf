// Khronos' own sample app (hello_xr from Debian's libopenxr-utils, unmodified) against xrsim on
// lavapipe with the Vulkan validation layer on.
#include <catch2/catch.hpp>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <string>

#include <nlohmann/json.hpp>

#include "child_process.hpp"
#include "test_support.hpp"
#include "vt/scene/image.hpp"

namespace {

struct ImageStats {
  double foregroundFraction = 0.0;  // pixels differing from the top-left (background) colour
  int pureFaces = 0;                // how many of red/green/blue cube faces appear
};

ImageStats stats(const vt::Image8& image) {
  ImageStats s;
  const std::uint8_t* bg = &image.pixels[0];
  std::size_t foreground = 0;
  bool red = false, green = false, blue = false;
  for (std::size_t i = 0; i < image.pixels.size(); i += 4) {
    const std::uint8_t r = image.pixels[i], g = image.pixels[i + 1], b = image.pixels[i + 2];
    if (std::abs(r - bg[0]) + std::abs(g - bg[1]) + std::abs(b - bg[2]) > 24) ++foreground;
    red |= r > 200 && g < 40 && b < 40;
    green |= g > 200 && r < 40 && b < 40;
    blue |= b > 200 && r < 40 && g < 40;
  }
  s.foregroundFraction = double(foreground) / double(image.pixels.size() / 4);
  s.pureFaces = int(red) + int(green) + int(blue);
  return s;
}

double differingFraction(const vt::Image8& a, const vt::Image8& b) {
  REQUIRE(a.pixels.size() == b.pixels.size());
  std::size_t differ = 0;
  for (std::size_t i = 0; i < a.pixels.size(); i += 4)
    if (std::abs(a.pixels[i] - b.pixels[i]) + std::abs(a.pixels[i + 1] - b.pixels[i + 1]) +
            std::abs(a.pixels[i + 2] - b.pixels[i + 2]) > 24)
      ++differ;
  return double(differ) / double(a.pixels.size() / 4);
}

}  // namespace

TEST_CASE("hello_xr runs 150 frames on xrsim with Vulkan2 and validation and shows its cubes") {
  const std::filesystem::path helloXr = VT_HELLO_XR;
  if (!std::filesystem::exists(helloXr)) VT_SKIP("hello_xr not installed (Debian package libopenxr-utils)");
  const auto dir = vt::test::outputDir("xrsim_hello_xr");

  // Squeeze both controllers from 0.5 s on: hello_xr then vibrates them (its grab action).
  nlohmann::json script = {{"keyframes",
                            {{{"t", 0.0}, {"left", {{"buttons", {{"squeeze", 0.0}}}}}, {"right", {{"buttons", {{"squeeze", 0.0}}}}}},
                             {{"t", 0.5}, {"left", {{"buttons", {{"squeeze", 0.0}}}}}, {"right", {{"buttons", {{"squeeze", 0.0}}}}}},
                             {{"t", 0.51}, {"left", {{"buttons", {{"squeeze", 1.0}}}}}, {"right", {{"buttons", {{"squeeze", 1.0}}}}}}}}};
  std::ofstream(dir / "script.json") << script.dump(2);

  std::map<std::string, std::string> env = {{"XR_RUNTIME_JSON", VT_XRSIM_MANIFEST},
                                            {"XRSIM_FRAMES", "150"},
                                            {"XRSIM_SAVE_EVERY", "60"},
                                            {"XRSIM_OUTPUT_DIR", dir.string()},
                                            {"XRSIM_SCRIPT", (dir / "script.json").string()},
                                            {"XRSIM_VALIDATION", "1"}};
#ifdef VT_ASAN_RUNTIME
  env.emplace("LD_PRELOAD", VT_ASAN_RUNTIME);  // xrsim is sanitized, hello_xr is not
  env.emplace("ASAN_OPTIONS", "detect_leaks=0");
#endif
  const auto result = vt::test::runChild({helloXr.string(), "-g", "Vulkan2"}, env, dir / "hello_xr.log", 300.0);
  INFO("hello_xr output in " << (dir / "hello_xr.log").string());
  REQUIRE_FALSE(result.timedOut);
  CHECK(result.exitCode == 0);
  // The layer really was active, and said nothing.
  CHECK(result.output.find("Inserted device layer \"VK_LAYER_KHRONOS_validation\"") != std::string::npos);
  CHECK(result.output.find("Validation Error") == std::string::npos);
  CHECK(result.output.find("VUID-") == std::string::npos);
  // The whole lifecycle, ending in EXITING after xrsim stopped the session.
  CHECK(result.output.find("XR_SESSION_STATE_READY->XR_SESSION_STATE_SYNCHRONIZED") != std::string::npos);
  CHECK(result.output.find("XR_SESSION_STATE_VISIBLE->XR_SESSION_STATE_FOCUSED") != std::string::npos);
  CHECK(result.output.find("XR_SESSION_STATE_IDLE->XR_SESSION_STATE_EXITING") != std::string::npos);

  // Frame 120 was submitted and captured (so at least 120 frames ran).
  for (int frame : {60, 120}) {
    char name[2][40];
    std::snprintf(name[0], sizeof(name[0]), "frame_%06d_left.png", frame);
    std::snprintf(name[1], sizeof(name[1]), "frame_%06d_right.png", frame);
    const auto left = vt::loadImage8(dir / name[0], 4);
    const auto right = vt::loadImage8(dir / name[1], 4);
    for (const auto* image : {&left, &right}) {
      const ImageStats s = stats(*image);
      INFO("frame " << frame << " foreground " << s.foregroundFraction << " faces " << s.pureFaces);
      CHECK(s.foregroundFraction > 0.03);  // cubes cover a visible part of the view
      CHECK(s.foregroundFraction < 0.60);  // and the clear colour the rest
      CHECK(s.pureFaces >= 2);             // hello_xr's cubes have pure red/green/blue faces
    }
    CHECK(differingFraction(left, right) > 0.002);  // the eyes are 64 mm apart
  }

  // Its grab action vibrated both controllers once the script squeezed them.
  std::ifstream log(dir / "haptics.jsonl");
  REQUIRE(log);
  std::map<std::string, int> perHand;
  std::string line;
  while (std::getline(log, line)) {
    const auto entry = nlohmann::json::parse(line);
    CHECK(entry["event"] == "apply");
    CHECK(entry["amplitude"].get<double>() == Approx(0.5));
    CHECK(entry["frame"].get<int>() >= 40);
    ++perHand[entry["hand"].get<std::string>()];
  }
  CHECK(perHand["left"] > 10);
  CHECK(perHand["right"] > 10);
}
