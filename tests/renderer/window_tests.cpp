// Window target and ImGui hook. Needs a display: ctest runs these under xvfb-run (see
// CMakeLists.txt); without DISPLAY they skip. Validation layer on, as everywhere.
#include <cstdlib>
#include <functional>
#include <string>

#include <GLFW/glfw3.h>
#include <catch2/catch.hpp>
#include <imgui.h>

#include "image_compare.hpp"
#include "render_fixture.hpp"
#include "test_support.hpp"
#include "vt/renderer/demo_frame.hpp"
#include "vt/renderer/imgui_layer.hpp"
#include "vt/renderer/renderer.hpp"
#include "vt/renderer/window_target.hpp"

using namespace vt;
using namespace vt::test;
using namespace vt::renderer;

namespace {

bool haveDisplay() { return std::getenv("DISPLAY") || std::getenv("WAYLAND_DISPLAY"); }

std::shared_ptr<Device> windowDevice() {
  DeviceOptions options;
  options.validate = true;
  addWindowExtensions(options);
  return Device::create(options);
}

WindowOptions goldenWindow() {
  WindowOptions options;
  options.width = int(kGoldenWidth);
  options.height = int(kGoldenHeight);
  options.resizable = true;
  options.title = "vt renderer test";
  return options;
}

/// Renders `frames` demo frames into the window and captures the last one.
Image8 renderAndCapture(Renderer& r, WindowTarget& window, const Scene& scene, int frames,
                        const std::function<void()>& ui = {}) {
  for (int i = 0; i < frames; ++i) {
    window.pollEvents();
    if (ui) ui();
    if (i == frames - 1) window.requestCapture();
    const VkExtent2D extent = window.extent();
    const FrameDesc frame = makeDemoFrame(scene, extent.width, extent.height, false, false);
    // A frame may be skipped while the swapchain is recreated; the capture waits for a drawn one.
    if (!r.render(window, frame) && i == frames - 1) --i;
  }
  return window.takeCapture();
}

}  // namespace

TEST_CASE("window swapchain shows the mono golden", "[renderer][.window]") {
  if (!haveDisplay()) VT_SKIP("no display (ctest runs this under xvfb-run)");
  auto device = windowDevice();
  {
    auto scene = std::make_shared<const Scene>(makeDemoScene());
    Renderer r(device);
    r.setScene(scene);
    WindowTarget window(device, goldenWindow());
    REQUIRE(window.extent().width == kGoldenWidth);
    REQUIRE(window.extent().height == kGoldenHeight);
    // Which present the ctest run must have taken (tests/renderer/CMakeLists.txt); on another
    // display (DRI3, a GPU) either is right.
    if (const char* expected = std::getenv("VT_EXPECT_PRESENT"))
      CHECK(std::string(window.hostPresent() ? "host" : "swapchain") == expected);
    checkGolden(renderAndCapture(r, window, *scene, 4), "render_mono");
  }
  expectNoValidationMessages(*device);
}

TEST_CASE("window swapchain is recreated after a resize", "[renderer][.window]") {
  if (!haveDisplay()) VT_SKIP("no display (ctest runs this under xvfb-run)");
  auto device = windowDevice();
  {
    auto scene = std::make_shared<const Scene>(makeDemoScene({.textureSize = 64}));
    Renderer r(device);
    r.setScene(scene);
    WindowTarget window(device, goldenWindow());
    renderAndCapture(r, window, *scene, 2);
    const std::uint64_t before = window.swapchainCount();
    glfwSetWindowSize(window.window(), 200, 120);
    // The X server applies the size asynchronously: keep drawing until the swapchain follows
    // (bounded by frames, not time).
    Image8 image;
    for (int attempt = 0; attempt < 200 && window.extent().width != 200; ++attempt) {
      image = renderAndCapture(r, window, *scene, 1);
    }
    image = renderAndCapture(r, window, *scene, 1);
    CHECK(window.swapchainCount() > before);
    CHECK(image.width == 200);
    CHECK(image.height == 120);
  }
  expectNoValidationMessages(*device);
}

TEST_CASE("imgui draws inside the scene pass", "[renderer][.window]") {
  if (!haveDisplay()) VT_SKIP("no display (ctest runs this under xvfb-run)");
  auto device = windowDevice();
  {
    auto scene = std::make_shared<const Scene>(makeDemoScene());
    Renderer r(device);
    r.setScene(scene);
    WindowTarget window(device, goldenWindow());
    ImGuiLayer ui(r, window);
    const Image8 image = renderAndCapture(r, window, *scene, 3, [&] {
      ui.beginFrame();
      ImGui::SetNextWindowPos({10, 10});
      ImGui::SetNextWindowSize({140, 60});
      ImGui::Begin("panel");
      ImGui::Text("haptics 1000 Hz");
      ImGui::End();
      ui.endFrame();
    });
    savePng(outputDir("imgui_window") / "capture.png", image);  // for a look when this fails
    const Image8 golden = loadImage8(sourceDir() / "tests/golden/render_mono.png", 4);
    // Inside the panel the picture changed; outside it is the golden scene.
    double inside = 0.0;
    int outsideMax = 0;
    for (int y = 0; y < image.height; ++y) {
      for (int x = 0; x < image.width; ++x) {
        const bool inPanel = x >= 10 && x < 150 && y >= 10 && y < 70;
        for (int c = 0; c < 3; ++c) {
          const int e = std::abs(int(image.at(x, y, c)) - int(golden.at(x, y, c)));
          if (inPanel) inside += e;
          else if (x > 155 || y > 75) outsideMax = std::max(outsideMax, e);  // skip a margin for the shadow
        }
      }
    }
    inside /= 140.0 * 60.0 * 3.0;
    INFO("mean error inside the panel " << inside << ", max outside " << outsideMax);
    CHECK(inside > 20.0);
    CHECK(outsideMax <= kBadPixelError);
  }
  expectNoValidationMessages(*device);
}
