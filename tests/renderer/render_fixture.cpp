#include "render_fixture.hpp"

#include <catch2/catch.hpp>

#include "vt/renderer/demo_frame.hpp"
#include "vt/renderer/offscreen_target.hpp"
#include "vt/renderer/renderer.hpp"

namespace vt::test {

std::shared_ptr<renderer::Device> validatingDevice() { return renderer::Device::create({.validate = true}); }

void expectNoValidationMessages(const renderer::Device& device) {
  INFO("validation messages are logged above");
  CHECK(device.validationEnabled());
  CHECK(device.validationMessageCount() == 0);
}

namespace {

std::vector<Image8> render(const DemoSceneOptions& options, bool stereo, bool overlay, renderer::HandStyle hand) {
  auto device = validatingDevice();
  std::vector<Image8> images;
  {
    auto scene = std::make_shared<const Scene>(makeDemoScene(options));
    renderer::Renderer r(device);
    r.setScene(scene);
    const renderer::FrameDesc frame = renderer::makeDemoFrame(*scene, kGoldenWidth, kGoldenHeight, stereo, overlay, hand);
    const auto layers = std::uint32_t(frame.views.size());
    renderer::OffscreenTarget target(device, kGoldenWidth, kGoldenHeight, layers);
    // Three frames: both frame slots and both target images are used, the last one is read back.
    for (int i = 0; i < 3; ++i) REQUIRE(r.render(target, frame));
    for (std::uint32_t layer = 0; layer < layers; ++layer) images.push_back(target.readback(layer));
  }
  expectNoValidationMessages(*device);
  return images;
}

}  // namespace

std::vector<Image8> renderDemo(const DemoSceneOptions& options, bool stereo, bool overlay, renderer::HandStyle hand) {
  return render(options, stereo, overlay, hand);
}

std::vector<Image8> renderFrame(const renderer::FrameDesc& frame) { return renderFrames({frame}).front(); }

std::vector<std::vector<Image8>> renderFrames(const std::vector<renderer::FrameDesc>& frames) {
  auto device = validatingDevice();
  std::vector<std::vector<Image8>> images;
  {
    auto scene = std::make_shared<const Scene>(makeDemoScene({}));
    renderer::Renderer r(device);
    r.setScene(scene);
    const auto layers = std::uint32_t(frames.front().views.size());
    renderer::OffscreenTarget target(device, kGoldenWidth, kGoldenHeight, layers);
    for (const renderer::FrameDesc& frame : frames) {
      for (int i = 0; i < 3; ++i) REQUIRE(r.render(target, frame));
      images.emplace_back();
      for (std::uint32_t layer = 0; layer < layers; ++layer) images.back().push_back(target.readback(layer));
    }
  }
  expectNoValidationMessages(*device);
  return images;
}

}  // namespace vt::test
