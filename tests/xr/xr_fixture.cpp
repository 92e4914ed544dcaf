#include "xr_fixture.hpp"

#include <catch2/catch.hpp>

#include <cmath>
#include <fstream>
#include <optional>

#include "vt/renderer/frame.hpp"

namespace vt::test {

ScopedEnv::ScopedEnv(const std::map<std::string, std::string>& vars) {
  for (const auto& [key, value] : vars) {
    const char* old = std::getenv(key.c_str());
    m_saved[key] = old ? std::optional<std::string>(old) : std::nullopt;
    setenv(key.c_str(), value.c_str(), 1);
  }
}

std::map<std::string, std::string> lookAtTableEnv(const std::filesystem::path& outputDir) {
  const float pitch = kTablePitch_rad;
  std::ofstream(outputDir / "script.json") << "{\"keyframes\": [{\"t\": 0, \"head\": {\"position\": [0, 1.6, 0], "
                                              "\"orientation\": [" << std::sin(pitch / 2) << ", 0, 0, "
                                           << std::cos(pitch / 2) << "]}}]}";
  auto env = xrsimEnv(outputDir, 12);
  env.insert_or_assign("XRSIM_SAVE_EVERY", std::string("10"));
  env.insert_or_assign("XRSIM_SCRIPT", std::string((outputDir / "script.json").string()));
  return env;
}

std::unique_ptr<xr::Headset> openValidatedHeadset(xr::HeadsetOptions options) {
  options.validate = true;
  auto opened = xr::Headset::open(options);
  INFO(opened.message);
  REQUIRE(opened.headset);
  return std::move(opened.headset);
}

ScopedEnv::~ScopedEnv() {
  for (const auto& [key, value] : m_saved) {
    if (value) setenv(key.c_str(), value->c_str(), 1);
    else unsetenv(key.c_str());
  }
}

std::map<std::string, std::string> xrsimEnv(const std::filesystem::path& outputDir, int stopAfterFrames) {
  return {{"XR_RUNTIME_JSON", VT_XRSIM_MANIFEST},
          {"XRSIM_OUTPUT_DIR", outputDir.string()},
          {"XRSIM_FRAMES", std::to_string(stopAfterFrames)},
          {"XRSIM_WIDTH", "256"},
          {"XRSIM_HEIGHT", "256"}};
}

xr::SessionPhase runLoop(xr::Headset& headset, renderer::Renderer& renderer, int maxIterations,
                         const std::function<void()>& perFrame, const PoseHistory* hand) {
  xr::SessionPhase phase = xr::SessionPhase::Idle;
  for (int i = 0; i < maxIterations; ++i) {
    phase = headset.pollEvents();
    if (phase == xr::SessionPhase::Exiting || phase == xr::SessionPhase::LossPending) return phase;
    if (phase != xr::SessionPhase::Running) continue;
    const bool rendered = headset.frame([&](int, const CameraView& view, renderer::RenderTarget& target) {
      renderer::FrameDesc frame;
      frame.views = {view};
      if (HandPose pose; hand && hand->newest(pose)) renderer::appendHand(pose, renderer::HandStyle::Mesh, frame);
      renderer.render(target, frame);
    });
    if (rendered && perFrame) perFrame();
  }
  return phase;
}

}  // namespace vt::test
