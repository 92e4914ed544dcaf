// The desktop preview in a real window (GLFW + Vulkan swapchain + Dear ImGui) with scripted input.
// Needs a display: ctest runs it under xvfb-run (app.desktop_golden_under_xvfb); skips without one.
#include <cmath>
#include <cstdlib>

#include <catch2/catch.hpp>

#include "modes/desktop_mode.hpp"
#include "test_support.hpp"
#include "vt/core/error.hpp"
#include "vt/scene/image.hpp"

using namespace vt;

namespace {

struct Difference {
  double psnr_db = 0.0;
  double badFraction = 0.0;  // pixels with a channel off by more than 40
};

Difference compare(const Image8& a, const Image8& b) {
  REQUIRE(a.width == b.width);
  REQUIRE(a.height == b.height);
  double squared = 0.0;
  std::size_t bad = 0;
  const std::size_t pixels = std::size_t(a.width) * std::size_t(a.height);
  for (std::size_t p = 0; p < pixels; ++p) {
    bool off = false;
    for (int c = 0; c < 3; ++c) {
      const int d = int(a.pixels[p * std::size_t(a.channels) + std::size_t(c)]) -
                    int(b.pixels[p * std::size_t(b.channels) + std::size_t(c)]);
      squared += double(d * d);
      off |= std::abs(d) > 40;
    }
    bad += off;
  }
  const double mse = squared / double(pixels * 3);
  return {mse == 0.0 ? 99.0 : 10.0 * std::log10(255.0 * 255.0 / mse), double(bad) / double(pixels)};
}

}  // namespace

TEST_CASE("Desktop preview in a window matches its golden screenshot", "[desktop]") {
  if (!app::haveDisplay()) VT_SKIP("no display (ctest runs this under xvfb-run)");
  const auto out = test::outputDir("app_desktop");
  app::DesktopOptions options;
  options.frames = 12;
  options.scripted = true;
  options.validate = true;
  options.screenshot = (out / "desktop.png").string();
  options.sinks.record = (out / "desktop.rec").string();
  REQUIRE(app::runDesktop(options) == 0);  // 3 would mean validation messages

  const Image8 actual = loadImage8(options.screenshot, 4);
  const auto golden = test::sourceDir() / "tests/app/golden/desktop.png";
  if (std::getenv("VT_UPDATE_GOLDENS")) {
    savePng(golden, actual);
    WARN("golden rewritten: " << golden.string());
  }
  const Image8 expected = loadImage8(golden, 4);
  // The scene and the scripted hand are deterministic; HUD figures (frame time, haptic rate,
  // plots) change from run to run, so the tolerance is a PSNR floor plus a small fraction of
  // clearly different pixels (the HUD text).
  const Difference d = compare(actual, expected);
  INFO("PSNR " << d.psnr_db << " dB, " << d.badFraction * 100.0 << " % pixels off by > 40 (actual: "
               << options.screenshot << ")");
  CHECK(d.psnr_db > 22.0);
  CHECK(d.badFraction < 0.03);

  // The hand is drawn: skin-coloured pixels around the scripted cursor path.
  int skin = 0;
  for (int y = actual.height / 4; y < actual.height * 3 / 4; ++y) {
    for (int x = actual.width / 3; x < actual.width * 2 / 3; ++x) {
      const int r = actual.at(x, y, 0), g = actual.at(x, y, 1), b = actual.at(x, y, 2);
      skin += r > 180 && g > 120 && g < 215 && b > 90 && b < 190 && r > g && g > b;
    }
  }
  CHECK(skin > 2000);
}
