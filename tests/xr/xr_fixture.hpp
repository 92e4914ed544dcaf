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

/// Polls and renders until the phase is no longer Idle/Running or maxIterations pass;
/// `perFrame` runs after each rendered frame. Returns the final phase.
xr::SessionPhase runLoop(xr::Headset& headset, renderer::Renderer& renderer, int maxIterations,
                         const std::function<void()>& perFrame = {});

}  // namespace vt::test
