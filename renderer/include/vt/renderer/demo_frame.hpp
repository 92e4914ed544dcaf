#pragma once
// The frame `vtouching render` and the golden-image tests draw, so both show the same picture.
#include <cstdint>

#include "vt/renderer/frame.hpp"
#include "vt/scene/scene.hpp"

namespace vt::renderer {

/// Interpupillary distance used for stereo renders (metres).
inline constexpr float kDefaultIpd_m = 0.064f;

/// The scene's orbit camera (stereo: two eyes kDefaultIpd_m apart, left first) and a posed right
/// hand hovering over the plates, drawn as `hand` says. Any thread.
FrameDesc makeDemoFrame(const Scene& scene, std::uint32_t width, std::uint32_t height, bool stereo, bool overlay,
                        HandStyle hand = HandStyle::Mesh);

}  // namespace vt::renderer
