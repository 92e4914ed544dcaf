#pragma once
// Renders the demo scene offscreen with the validation layer on, as every renderer test does.
#include <vector>

#include "vt/renderer/device.hpp"
#include "vt/renderer/frame.hpp"
#include "vt/scene/demo_scene.hpp"

namespace vt::test {

inline constexpr std::uint32_t kGoldenWidth = 320;
inline constexpr std::uint32_t kGoldenHeight = 180;

/// A validating device; the test fails if it saw any validation message by the end (call
/// expectNoValidationMessages after the renderer is gone).
std::shared_ptr<renderer::Device> validatingDevice();
void expectNoValidationMessages(const renderer::Device& device);

/// The demo frame (as `vtouching render` draws it) at the golden size: one image per view.
std::vector<Image8> renderDemo(const DemoSceneOptions& options, bool stereo, bool overlay,
                               renderer::HandStyle hand = renderer::HandStyle::Mesh);

/// `frame` over the demo scene at the golden size, one image per view.
std::vector<Image8> renderFrame(const renderer::FrameDesc& frame);

/// Each frame drawn over the default demo scene at the golden size into one target (three times,
/// so both frame slots are used), then read back: [frame][view].
std::vector<std::vector<Image8>> renderFrames(const std::vector<renderer::FrameDesc>& frames);

}  // namespace vt::test
