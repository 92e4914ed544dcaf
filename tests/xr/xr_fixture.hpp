#pragma once
// Runs vt::xr against xrsim: environment set-up and a frame loop drawing the demo scene.
#include <cstdlib>
#include <filesystem>
#include <functional>
#include <map>
#include <optional>
#include <memory>
#include <string>

#include "vt/renderer/renderer.hpp"
#include "vt/xr/headset.hpp"

namespace vt::test {

/// Sets environment variables for the scope (the loader and xrsim read them at xrCreateInstance).
class ScopedEnv {
 public:
  explicit ScopedEnv(const std::map<std::string, std::string>& vars);
  ~ScopedEnv();

 private:
  std::map<std::string, std::optional<std::string>> m_saved;
};

/// The xrsim settings every test starts from (manifest, validation, output folder).
std::map<std::string, std::string> xrsimEnv(const std::filesystem::path& outputDir, int stopAfterFrames);

/// How far the head in lookAtTableEnv is pitched down.
inline constexpr float kTablePitch_rad = -0.9f;
/// xrsim settings for a run where the user looks down at the table (head at 1.6 m, pitched
/// kTablePitch_rad), 12 frames, saving frame 10 into outputDir (writes the script there).
std::map<std::string, std::string> lookAtTableEnv(const std::filesystem::path& outputDir);

/// Options with the scene fixed at HeadsetOptions::T_stage_world whatever the head does, for
/// tests that script the hand or the eyes in stage coordinates.
inline xr::HeadsetOptions fixedPlacement() {
  xr::HeadsetOptions options;
  options.placeAtHead = false;
  return options;
}

/// Opens the headset with the validation layer on; fails the test (with the runtime's message)
/// when it cannot be opened.
std::unique_ptr<xr::Headset> openValidatedHeadset(xr::HeadsetOptions options = {});

/// Polls and renders until the phase is no longer Idle/Running or maxIterations pass;
/// `perFrame` runs after each rendered frame; `hand`: its newest pose is drawn (skinned mesh).
/// Returns the final phase.
xr::SessionPhase runLoop(xr::Headset& headset, renderer::Renderer& renderer, int maxIterations,
                         const std::function<void()>& perFrame = {}, const PoseHistory* hand = nullptr);

}  // namespace vt::test
